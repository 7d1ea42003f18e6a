#pragma once
// Whether this test binary runs under a sanitizer (ASan, TSan: GCC's and Clang's spellings),
// where the code runs 10-20 times slower: the few tests whose size is their point keep a size
// that still shows it, not the Release one.
namespace edacrt::test {

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
inline constexpr bool kSanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
inline constexpr bool kSanitized = true;
#else
inline constexpr bool kSanitized = false;
#endif
#else
inline constexpr bool kSanitized = false;
#endif

}  // namespace edacrt::test
