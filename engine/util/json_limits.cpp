#include "util/json_limits.h"

#include "util/error.h"
#include "util/printable.h"

namespace edacrt {

void check_json_depth(std::string_view text, const std::string& source, int max_depth) {
    int depth = 0;
    JsonStrings strings;
    std::size_t line = 1, line_start = 0;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (c == '\n') {
            ++line;
            line_start = i + 1;
        }
        if (!strings.outside(c)) continue;
        if (c == '[' || c == '{') {
            if (++depth > max_depth)
                throw InputError(source + ":" + std::to_string(line) + ":" +
                                 std::to_string(i - line_start + 1) + ": JSON nested deeper than " +
                                 std::to_string(max_depth) + " levels");
        } else if ((c == ']' || c == '}') && depth > 0) {
            --depth;
        }
    }
}

std::string shorten(std::string_view text, std::size_t max_length) {
    if (text.size() <= max_length) return std::string(text);
    return std::string(text.substr(0, max_length)) + "...";
}

std::string json_excerpt(const nlohmann::json& value, std::size_t max_length) {
    // The replace handler: a string of invalid UTF-8 must not throw while a message is made.
    // dump() escapes only controls below 0x20: DEL and U+0080..U+009F are escaped here.
    return printable(value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace),
                     max_length);
}

nlohmann::json parse_json(std::string_view text, const std::string& source) {
    check_json_depth(text, source);
    try {
        return nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {  // out_of_range too: a number such as 1e999
        // The error quotes the token it stopped in, which may be a whole long string, with its
        // DEL and invalid UTF-8 bytes as they are.
        throw InputError(source + ": not valid JSON: " + printable(e.what(), 240));
    }
}

}  // namespace edacrt
