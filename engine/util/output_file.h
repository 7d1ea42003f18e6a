#pragma once
// A file written with every error checked, the final flush and close included: a full disk
// (or /dev/full) fails the command instead of leaving a truncated file behind silently.
// A regular file (or a new one) is written to a temporary file beside it and renamed over it
// only once complete, so a failed write leaves the old file as it was.
#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace edacrt {

class OutputFile {
  public:
    /// Starts writing `path`; `what` names the content in messages ("PNG", "hit file").
    /// Throws InputError when the file (or its temporary) cannot be created.
    OutputFile(const std::filesystem::path& path, std::string what);
    ~OutputFile();  // an unclosed file (an error path) is abandoned: its temporary removed
    OutputFile(const OutputFile&) = delete;
    OutputFile& operator=(const OutputFile&) = delete;

    /// Appends bytes. The first error is kept and reported by close(); later writes do nothing.
    void write(const void* data, std::size_t size);
    void write(std::string_view text) { write(text.data(), text.size()); }

    /// Flushes, closes and renames the temporary over the file; throws InputError naming the
    /// file and the first error, the old file left untouched.
    void close();

  private:
    std::filesystem::path path_;    // as given, for messages
    std::filesystem::path target_;  // where the content ends up (a symbolic link resolved)
    std::filesystem::path temp_;    // empty: written in place (a device, a FIFO)
    std::string what_;
    std::FILE* file_ = nullptr;
    int error_ = 0;  // errno of the first failure
};

/// Creates the folders `file` is to be written in; throws InputError naming the folder when
/// they cannot be made or written to (a file where a folder should be, no permission).
void create_parent_folders(const std::filesystem::path& file);

/// Writes `bytes` as the whole content of `path` through OutputFile.
void write_file(const std::filesystem::path& path, std::string_view bytes, std::string what);

/// Throws InputError when `path` could not be written by OutputFile (its folder refuses a
/// temporary, or the existing file is read-only), so a long run fails before its work rather
/// than at its end. Creates nothing that stays.
void check_output_file(const std::filesystem::path& path, std::string_view what);

/// What tells files apart when the content of `path` is written: the same string for every
/// name of one file (after resolving "..", symbolic links and hard links); nullopt for devices
/// and FIFOs (/dev/null, /dev/stdout), which are written in place and may be shared.
std::optional<std::string> output_identity(const std::filesystem::path& path);

/// True when `a` and `b` name the same output file (after resolving "..", symbolic links and
/// hard links). Devices and FIFOs (/dev/null, /dev/stdout) are never the same output.
bool same_output_file(const std::filesystem::path& a, const std::filesystem::path& b);

/// A file a command names (on its command line, in a script): what names it, and the path.
struct NamedPath {
    std::string option;  // "--out"
    std::string path;    // empty: not given
};

/// Throws InputError before any work when two outputs name the same file (the second would
/// silently replace the first), or an output names an input (read, then overwritten), through
/// symbolic or hard links too. Devices such as /dev/null and /dev/stdout may be shared; inputs
/// that are not files (builtin:...) are skipped.
void check_distinct_files(const std::vector<NamedPath>& outputs,
                          const std::vector<NamedPath>& inputs = {});

}  // namespace edacrt
