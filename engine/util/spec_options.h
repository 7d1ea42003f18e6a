#pragma once
// "NAME:key=value,key=value" strings that name a built-in scene or an animation on the command
// line and in the viewer: parsed once here, each value taken (and range-checked) by its user.
#include <charconv>
#include <cstdio>
#include <map>
#include <string>
#include <string_view>
#include <type_traits>

#include "util/error.h"

namespace edacrt {

class SpecOptions {
  public:
    /// `spec` is the whole string (for messages); `list` its "key=value,..." part, possibly
    /// empty. Throws InputError for an item without '=' or a key given twice.
    SpecOptions(std::string_view spec, std::string_view list);

    /// Takes `key` as a number in [lo, hi], or returns `fallback` when it is absent. Throws
    /// InputError naming the key, the range and the text otherwise (NaN is never in range).
    template <typename T>
    T number(const char* key, T fallback, T lo, T hi) {
        const auto it = values_.find(key);
        if (it == values_.end()) return fallback;
        const std::string text = it->second;
        values_.erase(it);
        T value{};
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (ec != std::errc() || end != text.data() + text.size() || !(value >= lo && value <= hi))
            throw InputError(spec_ + ": " + key + " must be a number in [" + format(lo) + ", " +
                             format(hi) + "], got '" + text + "'");
        return value;
    }

    /// Takes `key` as text, or returns `fallback` when it is absent.
    std::string text(const char* key, std::string fallback);

    /// Throws InputError naming the first key no one took.
    void finish() const;

  private:
    template <typename T>
    static std::string format(T value) {
        if constexpr (std::is_integral_v<T>) {
            return std::to_string(value);
        } else {
            char text[32];
            std::snprintf(text, sizeof text, "%g", double(value));
            return text;
        }
    }

    std::string spec_;
    std::map<std::string, std::string, std::less<>> values_;
};

/// The shortest text that reads back as `x` (for specs that must make the same thing again).
std::string shortest_text(double x);

}  // namespace edacrt
