#include "scene/text_scan.h"

#include <charconv>
#include <cmath>
#include <system_error>

namespace edacrt::text_scan {

std::string escape(std::string_view text) {
    std::string out;
    for (const char c : text) {
        const auto u = static_cast<unsigned char>(c);
        if (u >= 0x20 && u != 0x7f) {
            out += c;
        } else {
            constexpr char kHex[] = "0123456789ABCDEF";
            out += "\\x";
            out += kHex[u >> 4];
            out += kHex[u & 15];
        }
    }
    return out;
}

std::string quote(std::string_view text) {
    constexpr std::size_t kMax = 40;
    return "'" + escape(text.substr(0, kMax)) + (text.size() > kMax ? "...'" : "'");
}

/// Parses a whole token as a finite float. from_chars is exact and allocation-free, but rejects
/// a leading '+' and reports underflow as out of range; both are accepted here.
NumberStatus parse_float(std::string_view token, float& value) {
    const char* first = token.data();
    const char* last = first + token.size();
    if (first != last && *first == '+') {
        ++first;
        if (first != last && *first == '-') return NumberStatus::malformed;
    }
    const auto [end, ec] = std::from_chars(first, last, value);
    if (ec == std::errc::invalid_argument || end != last) return NumberStatus::malformed;
    if (ec == std::errc::result_out_of_range) {
        double wide = 0.0;
        const auto [wide_end, wide_ec] = std::from_chars(first, last, wide);
        if (wide_ec != std::errc{} || !(std::abs(wide) < 1.0)) return NumberStatus::out_of_range;
        value = static_cast<float>(wide);  // a value below float's range becomes 0 or subnormal
    }
    return std::isfinite(value) ? NumberStatus::ok : NumberStatus::non_finite;
}

std::string describe(NumberStatus status, std::string_view token) {
    switch (status) {
        case NumberStatus::ok:
            break;
        case NumberStatus::malformed:
            return "bad number " + quote(token);
        case NumberStatus::non_finite:
            return "non-finite number " + quote(token);
        case NumberStatus::out_of_range:
            return "number " + quote(token) + " is out of range for float";
    }
    return "number " + quote(token);
}

}  // namespace edacrt::text_scan
