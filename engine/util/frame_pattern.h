#pragma once
// File names numbered by frame, printf style ("frames/name_%04d.obj", "out/frame_%04d.png"):
// the OBJ key frames of a sequence and the images of `edacrt render --frames`.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace edacrt {

class FramePattern {
  public:
    /// `pattern` holds exactly one %d or %0Nd (N <= 9) in its file name, and %% for a literal
    /// '%'. Throws InputError otherwise, naming `what` ("--out", "sequence pattern").
    FramePattern(std::string pattern, std::string_view what);

    /// The path of frame `index` (>= 0), as printf would write it.
    std::filesystem::path path(std::int64_t index) const;

    /// The frame number when `file_name` (no directory) is one this pattern writes.
    std::optional<std::int64_t> match(std::string_view file_name) const;

    /// The directory the files are in ("." when the pattern has none).
    std::filesystem::path directory() const;

    const std::string& pattern() const { return pattern_; }

    /// A name without a frame number as printf would write it: %% as %. Throws InputError for
    /// a lone %, naming `what`.
    static std::string literal(std::string_view text, std::string_view what);

    /// True when `text` holds a % conversion at all (so a single output may be told apart).
    static bool has_conversion(std::string_view text);

  private:
    std::string pattern_;
    std::filesystem::path directory_;
    std::string prefix_, suffix_;  // of the file name, %% already replaced by %
    int width_ = 0;                // %0Nd: at least N digits, zero-padded
};

}  // namespace edacrt
