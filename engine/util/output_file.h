#pragma once
// A file written with every error checked, the final flush and close included: a full disk
// (or /dev/full) fails the command instead of leaving a truncated file behind silently.
#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>

namespace edacrt {

class OutputFile {
  public:
    /// Creates or truncates `path`; `what` names the content in messages ("PNG", "hit file").
    /// Throws InputError when the file cannot be created.
    OutputFile(const std::filesystem::path& path, std::string what);
    ~OutputFile();  // closes without reporting: only reached unclosed on an error path
    OutputFile(const OutputFile&) = delete;
    OutputFile& operator=(const OutputFile&) = delete;

    /// Appends bytes. The first error is kept and reported by close(); later writes do nothing.
    void write(const void* data, std::size_t size);
    void write(std::string_view text) { write(text.data(), text.size()); }

    /// Flushes and closes; throws InputError naming the file and the first error.
    void close();

  private:
    std::filesystem::path path_;
    std::string what_;
    std::FILE* file_ = nullptr;
    int error_ = 0;  // errno of the first failure
};

/// Creates the folders `file` is to be written in; throws InputError naming the folder when
/// they cannot be made or written to (a file where a folder should be, no permission).
void create_parent_folders(const std::filesystem::path& file);

/// Writes `bytes` as the whole content of `path` through OutputFile.
void write_file(const std::filesystem::path& path, std::string_view bytes, std::string what);

}  // namespace edacrt
