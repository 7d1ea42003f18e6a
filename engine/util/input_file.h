#pragma once
// Whole small files read with a bound: a FIFO, a device (/dev/zero) or a directory is refused
// before any read, and a file over its cap is refused with its size, so a wrong path can
// neither hang a command nor fill the memory.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace edacrt {

/// Caps for the small text files the programs read (JSON, scripts): far above any real one.
constexpr std::uint64_t kMaxTextFileBytes = 64ull << 20;

/// Throws InputError unless `path` is a regular file of at most `max_bytes` bytes; returns its
/// size. `what` names the content in messages ("animation file"). Opens with O_NONBLOCK, so a
/// FIFO cannot block the check.
std::uint64_t check_input_file(const std::filesystem::path& path, std::string_view what,
                               std::uint64_t max_bytes);

/// The whole of `path` after check_input_file(); a file that grows past `max_bytes` while
/// read (or a /proc file that reports no size) is refused too.
std::string read_text_file(const std::filesystem::path& path, std::string_view what,
                           std::uint64_t max_bytes = kMaxTextFileBytes);

}  // namespace edacrt
