#pragma once
// Bounds on JSON read from files: a nesting depth checked before parsing (nlohmann's dump and
// destructor recurse once per level, so 60,000 '[' would overflow the stack), and short
// excerpts of values and parser errors for messages.
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace edacrt {

constexpr int kMaxJsonDepth = 64;

/// Follows a JSON text one character at a time to tell its structure from string contents.
class JsonStrings {
  public:
    /// Steps over `c`; true when it is structure (outside every string, not a quote).
    bool outside(char c) {
        if (in_string_) {
            if (escaped_)
                escaped_ = false;
            else if (c == '\\')
                escaped_ = true;
            else if (c == '"')
                in_string_ = false;
            return false;
        }
        in_string_ = c == '"';
        return !in_string_;
    }

  private:
    bool in_string_ = false, escaped_ = false;
};

/// Throws InputError ("SOURCE:LINE:COLUMN: ...") when arrays and objects in `text` nest deeper
/// than `max_depth`. Brackets inside strings do not count.
void check_json_depth(std::string_view text, const std::string& source,
                      int max_depth = kMaxJsonDepth);

/// `text` cut to `max_length` bytes with "..." when longer.
std::string shorten(std::string_view text, std::size_t max_length = 80);

/// A value as compact JSON for a message, printable() and cut to `max_length`.
std::string json_excerpt(const nlohmann::json& value, std::size_t max_length = 80);

/// check_json_depth(), then nlohmann's parser; a parse error becomes an InputError naming
/// `source`, its excerpt of the text printable() and cut.
nlohmann::json parse_json(std::string_view text, const std::string& source);

}  // namespace edacrt
