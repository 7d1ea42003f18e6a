#include "scene/text_scan.h"

#include <charconv>
#include <cmath>
#include <system_error>

namespace edacrt::text_scan {

namespace {

/// The length of the valid UTF-8 sequence for a character beyond ASCII at the start of `text`,
/// or 0 (invalid, overlong, a surrogate, or a C1 control character).
std::size_t utf8_length(std::string_view text) {
    const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
    const unsigned char lead = byte(0);
    std::size_t length = 0;
    unsigned char low = 0x80, high = 0xBF;  // the range of the second byte
    if (lead >= 0xC2 && lead <= 0xDF) {
        length = 2;
        if (lead == 0xC2) low = 0xA0;  // U+0080..U+009F are control characters
    } else if (lead >= 0xE0 && lead <= 0xEF) {
        length = 3;
        if (lead == 0xE0) low = 0xA0;
        if (lead == 0xED) high = 0x9F;
    } else if (lead >= 0xF0 && lead <= 0xF4) {
        length = 4;
        if (lead == 0xF0) low = 0x90;
        if (lead == 0xF4) high = 0x8F;
    }
    if (length == 0 || text.size() < length || byte(1) < low || byte(1) > high) return 0;
    for (std::size_t i = 2; i < length; ++i)
        if (byte(i) < 0x80 || byte(i) > 0xBF) return 0;
    return length;
}

}  // namespace

std::string escape(std::string_view text, std::size_t max_length) {
    std::string out;
    std::size_t i = 0;
    while (i < text.size() && i < max_length) {
        const auto c = static_cast<unsigned char>(text[i]);
        if (c >= 0x20 && c < 0x7f) {
            out += static_cast<char>(c);
            ++i;
        } else if (const std::size_t n = c >= 0x80 ? utf8_length(text.substr(i)) : 0; n > 0) {
            if (i + n > max_length) break;  // not cut in the middle of a character
            out += text.substr(i, n);
            i += n;
        } else {
            constexpr char kHex[] = "0123456789ABCDEF";
            out += "\\x";
            out += kHex[c >> 4];
            out += kHex[c & 15];
            ++i;
        }
    }
    if (i < text.size()) out += "...";
    return out;
}

std::string quote(std::string_view text) {
    // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string&&.
    std::string out = "'";
    out.append(escape(text, 40)).append("'");
    return out;
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
