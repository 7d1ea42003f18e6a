#pragma once
// Line and token scanning shared by the OBJ and MTL parsers: views into the file text, no
// allocation per line, numbers parsed exactly with from_chars.
#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace edacrt::text_scan {

inline bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\v' || c == '\f'; }

inline char to_lower(char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; }

inline bool equals_ignoring_case(std::string_view a, std::string_view b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (to_lower(a[i]) != to_lower(b[i])) return false;
    return true;
}

inline bool is_keyword(std::string_view word) {
    const auto alpha = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); };
    if (word.empty() || !alpha(word[0])) return false;
    for (char c : word)
        if (!alpha(c) && !(c >= '0' && c <= '9') && c != '_') return false;
    return true;
}

/// Text from a file for a message: printable() cut after `max_length` bytes.
std::string escape(std::string_view text, std::size_t max_length = 60);

/// A token for a message: escape()d to 40 bytes, in single quotes.
std::string quote(std::string_view text);

/// Warnings of one kind (an undefined material, an invalid Ni): the first kWarningsPerKind are
/// kept, the rest only counted, so that a file with thousands of them cannot flood the output
/// (20,000 undefined materials printed 2.8 MB).
class WarningLimit {
  public:
    static constexpr std::size_t kWarningsPerKind = 10;

    /// `what`: the kind in the plural, for "... and N more undefined materials".
    explicit WarningLimit(std::string what) : what_(std::move(what)) {}

    void add(std::vector<std::string>& warnings, std::string warning) {
        if (count_++ < kWarningsPerKind) warnings.push_back(std::move(warning));
    }

    /// Reports how many were left out, once, naming `source`.
    void finish(std::vector<std::string>& warnings, const std::string& source) const {
        if (count_ > kWarningsPerKind)
            warnings.push_back(source + ": ... and " + std::to_string(count_ - kWarningsPerKind) +
                               " more " + what_);
    }

  private:
    std::string what_;
    std::size_t count_ = 0;
};

/// The lines of a text, split at "\n", "\r\n" or a lone "\r" (classic Mac files), so that line
/// numbers match what an editor shows. A UTF-8 byte order mark is skipped.
class LineReader {
  public:
    explicit LineReader(std::string_view text) : text_(text) {
        if (text_.starts_with("\xEF\xBB\xBF")) text_.remove_prefix(3);
    }

    bool next(std::string_view& line) {
        if (text_.empty()) return false;
        std::size_t end = 0;
        while (end < text_.size() && text_[end] != '\n' && text_[end] != '\r') ++end;
        line = text_.substr(0, end);
        std::size_t skip = end;
        if (skip < text_.size()) skip += text_.compare(skip, 2, "\r\n") == 0 ? 2 : 1;
        text_.remove_prefix(skip);
        ++number_;
        return true;
    }

    std::size_t number() const { return number_; }

  private:
    std::string_view text_;
    std::size_t number_ = 0;
};

/// Blank-separated tokens of one line, as views into the text.
class Tokens {
  public:
    explicit Tokens(std::string_view line) : rest_(line) {}

    bool next(std::string_view& token) {
        skip_blanks();
        if (rest_.empty()) return false;
        std::size_t end = 0;
        while (end < rest_.size() && !is_blank(rest_[end])) ++end;
        token = rest_.substr(0, end);
        rest_.remove_prefix(end);
        return true;
    }

    /// The rest of the line without surrounding blanks (a name may contain spaces).
    std::string_view rest() {
        skip_blanks();
        while (!rest_.empty() && is_blank(rest_.back())) rest_.remove_suffix(1);
        return rest_;
    }

  private:
    void skip_blanks() {
        while (!rest_.empty() && is_blank(rest_.front())) rest_.remove_prefix(1);
    }

    std::string_view rest_;
};

/// The statement part of a line: a comment runs from '#' to the end of the line.
inline std::string_view strip_comment(std::string_view line) {
    line = line.substr(0, line.find('#'));
    while (!line.empty() && is_blank(line.back())) line.remove_suffix(1);
    return line;
}

enum class NumberStatus { ok, malformed, non_finite, out_of_range };

/// Parses a whole token as a finite float. from_chars is exact and allocation-free, but rejects
/// a leading '+' and reports underflow as out of range; both are accepted here.
NumberStatus parse_float(std::string_view token, float& value);

/// What is wrong with a number that did not parse, for an error message.
std::string describe(NumberStatus status, std::string_view token);

}  // namespace edacrt::text_scan
