#include "scene/text_scan.h"

#include <charconv>
#include <cmath>
#include <system_error>

#include "util/printable.h"

namespace edacrt::text_scan {

std::string escape(std::string_view text, std::size_t max_length) {
    return printable(text, max_length);
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
