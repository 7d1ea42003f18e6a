#include "util/frame_pattern.h"

#include <charconv>

#include "util/error.h"

namespace edacrt {
namespace {

/// `text` with %% replaced by %; throws for any other lone '%'.
std::string unescape(std::string_view text, const std::string& pattern, std::string_view what) {
    std::string out;
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text[i] != '%') {
            out += text[i];
            continue;
        }
        if (i + 1 < text.size() && text[i + 1] == '%') {
            out += '%';
            ++i;
            continue;
        }
        throw InputError(std::string(what) + " '" + pattern +
                         "': only one %d or %0Nd is allowed (write %% for a literal %)");
    }
    return out;
}

}  // namespace

bool FramePattern::has_conversion(std::string_view text) {
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text[i] != '%') continue;
        if (i + 1 < text.size() && text[i + 1] == '%') {
            ++i;
            continue;
        }
        return true;
    }
    return false;
}

std::string FramePattern::literal(std::string_view text, std::string_view what) {
    return unescape(text, std::string(text), what);
}

FramePattern::FramePattern(std::string pattern, std::string_view what)
    : pattern_(std::move(pattern)) {
    const std::filesystem::path path(pattern_);
    const std::string name = path.filename().string();
    const std::string directory = path.has_parent_path() ? path.parent_path().string() : ".";
    if (FramePattern::has_conversion(directory))
        throw InputError(std::string(what) + " '" + pattern_ +
                         "': the frame number must be in the file name, not the directory");
    directory_ = unescape(directory, pattern_, what);  // a folder may hold %% too
    // The conversion: the first '%' not part of "%%".
    std::size_t at = std::string::npos;
    for (std::size_t i = 0; i < name.size(); ++i) {
        if (name[i] != '%') continue;
        if (i + 1 < name.size() && name[i + 1] == '%') {
            ++i;
            continue;
        }
        at = i;
        break;
    }
    if (at == std::string::npos)
        throw InputError(std::string(what) + " '" + pattern_ +
                         "' has no frame number: write %d or %04d where it goes");
    std::size_t end = at + 1;
    if (end < name.size() && name[end] == '0') {
        std::size_t digits = end + 1;
        while (digits < name.size() && name[digits] >= '0' && name[digits] <= '9') ++digits;
        const auto [ptr, ec] = std::from_chars(name.data() + end + 1, name.data() + digits, width_);
        if (ec != std::errc() || ptr != name.data() + digits || width_ < 1 || width_ > 9)
            throw InputError(std::string(what) + " '" + pattern_ +
                             "': the frame number is %d or %0Nd with N from 1 to 9");
        end = digits;
    }
    if (end >= name.size() || name[end] != 'd')
        throw InputError(std::string(what) + " '" + pattern_ +
                         "': the frame number is %d or %0Nd with N from 1 to 9");
    prefix_ = unescape(std::string_view(name).substr(0, at), pattern_, what);
    suffix_ = unescape(std::string_view(name).substr(end + 1), pattern_, what);
}

std::filesystem::path FramePattern::path(std::int64_t index) const {
    std::string digits = std::to_string(index);
    if (digits.size() < std::size_t(width_))
        digits.insert(0, std::size_t(width_) - digits.size(), '0');
    const std::string name = prefix_ + digits + suffix_;
    return std::filesystem::path(pattern_).has_parent_path() ? directory_ / name
                                                             : std::filesystem::path(name);
}

std::optional<std::int64_t> FramePattern::match(std::string_view file_name) const {
    if (file_name.size() <= prefix_.size() + suffix_.size() || !file_name.starts_with(prefix_) ||
        !file_name.ends_with(suffix_))
        return std::nullopt;
    const std::string_view digits =
        file_name.substr(prefix_.size(), file_name.size() - prefix_.size() - suffix_.size());
    std::int64_t index = 0;
    const auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), index);
    if (ec != std::errc() || ptr != digits.data() + digits.size() || index < 0) return std::nullopt;
    // Only the spelling printf gives this number: "%04d" writes 12 as 0012, never 12 or 00012.
    if (path(index).filename().string() != file_name) return std::nullopt;
    return index;
}

std::filesystem::path FramePattern::directory() const { return directory_; }

}  // namespace edacrt
