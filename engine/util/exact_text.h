#pragma once
// Numbers as text that reads back to the same value: nine significant digits for a float,
// seventeen for a double (the fewest that always round-trip), vectors comma-separated as the
// command line's --eye X,Y,Z takes them; and the reading back.
#include <charconv>
#include <cmath>
#include <cstdio>
#include <glm/vec3.hpp>
#include <optional>
#include <string>
#include <string_view>

namespace edacrt {

inline std::string exact_text(float v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", double(v));
    return text;
}

inline std::string exact_text(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", v);
    return text;
}

inline std::string exact_text(const glm::vec3& v) {
    return exact_text(v.x) + "," + exact_text(v.y) + "," + exact_text(v.z);
}

/// The whole of `text` as a finite number (exactly, as from_chars reads it); nothing when it is
/// not one, has more after the number, or is inf or NaN.
inline std::optional<double> parse_number(std::string_view text) {
    double value = 0.0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc{} || end != text.data() + text.size() || !std::isfinite(value))
        return std::nullopt;
    return value;
}

}  // namespace edacrt
