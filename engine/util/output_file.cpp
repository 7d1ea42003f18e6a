#include "util/output_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <map>
#include <optional>
#include <string>
#include <utility>

#include "util/error.h"

namespace edacrt {
namespace {

namespace fs = std::filesystem;

/// Devices, FIFOs and /proc are written in place: they cannot be replaced by a rename, and
/// /dev/stdout must reach the process's own standard output.
bool written_in_place(const fs::path& path) {
    std::error_code ec;
    const std::string text = fs::absolute(path, ec).lexically_normal().string();
    if (text.starts_with("/dev/") || text.starts_with("/proc/")) return true;
    struct stat status {};
    return ::stat(path.c_str(), &status) == 0 && !S_ISREG(status.st_mode);
}

/// Where a rename must put the content: a symbolic link is kept and its target replaced.
fs::path rename_target(const fs::path& path) {
    std::error_code ec;
    if (!fs::is_symlink(fs::symlink_status(path, ec))) return path;
    const fs::path target = fs::canonical(path, ec);
    // A loop names no file to write: replacing it would silently undo someone's links.
    if (ec == std::errc::too_many_symbolic_link_levels)
        throw InputError(path.string() + ": a loop of symbolic links; not replaced");
    return ec ? path : target;  // a dangling link: replaced by the file
}

/// The reason a temporary file could not be made, saying so unless the folder is missing.
std::string temporary_error(int error) {
    return std::string(std::strerror(error)) +
           (error == ENOENT || error == ENOTDIR ? "" : ", for a temporary file beside it");
}

/// Creates a new, unique file beside `target`; returns its descriptor (-1 with errno set).
int open_temporary(const fs::path& target, fs::path& temp) {
    static std::atomic<unsigned> counter{0};
    for (int attempt = 0; attempt < 100; ++attempt) {
        temp = target;
        temp += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
        // 0666 and O_EXCL: the permissions a new file gets under the umask, and no clobbering.
        const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd >= 0 || errno != EEXIST) return fd;
    }
    return -1;
}

}  // namespace

OutputFile::OutputFile(const std::filesystem::path& path, std::string what)
    : path_(path), target_(path), what_(std::move(what)) {
    if (written_in_place(path)) {
        file_ = std::fopen(path.c_str(), "wb");
        if (!file_)
            throw InputError(path_.string() + ": cannot create " + what_ + " (" +
                             std::strerror(errno) + ")");
        return;
    }
    target_ = rename_target(path);
    const int fd = open_temporary(target_, temp_);
    if (fd < 0) {
        const int error = errno;
        temp_.clear();
        throw InputError(path_.string() + ": cannot create " + what_ + " (" +
                         temporary_error(error) + ")");
    }
    // The replacement keeps the permissions of the file it replaces.
    struct stat old {};
    if (::stat(target_.c_str(), &old) == 0) ::fchmod(fd, old.st_mode & 07777);
    file_ = ::fdopen(fd, "wb");
    if (!file_) {
        const int error = errno;
        ::close(fd);
        ::unlink(temp_.c_str());
        temp_.clear();
        throw InputError(path_.string() + ": cannot create " + what_ + " (" + std::strerror(error) +
                         ")");
    }
}

OutputFile::~OutputFile() {
    if (file_) std::fclose(file_);
    if (!temp_.empty()) ::unlink(temp_.c_str());
}

void OutputFile::write(const void* data, std::size_t size) {
    if (error_ || size == 0) return;
    errno = 0;
    if (std::fwrite(data, 1, size, file_) != size) error_ = errno ? errno : EIO;
}

void OutputFile::close() {
    if (!file_) return;
    // Buffered data reaches the file only here, so this is where a full disk shows.
    errno = 0;
    if (std::fflush(file_) != 0 && !error_) error_ = errno ? errno : EIO;
    // Data on disk before the rename, so a crash leaves the old file or the new, not nothing.
    if (!temp_.empty() && !error_ && ::fsync(::fileno(file_)) != 0) error_ = errno;
    errno = 0;
    if (std::fclose(std::exchange(file_, nullptr)) != 0 && !error_) error_ = errno ? errno : EIO;
    if (!error_ && !temp_.empty() && std::rename(temp_.c_str(), target_.c_str()) != 0)
        error_ = errno;
    if (!error_) temp_.clear();  // renamed: nothing left to remove
    if (!temp_.empty()) {
        ::unlink(temp_.c_str());
        temp_.clear();
    }
    if (error_)
        throw InputError(path_.string() + ": cannot write " + what_ + " (" + std::strerror(error_) +
                         (written_in_place(path_) ? ")" : "; the old file, if any, is unchanged)"));
}

void write_file(const std::filesystem::path& path, std::string_view bytes, std::string what) {
    OutputFile file(path, std::move(what));
    file.write(bytes);
    file.close();
}

void check_output_file(const std::filesystem::path& path, std::string_view what) {
    std::error_code ec;
    if (fs::is_directory(path, ec))
        throw InputError(path.string() + ": is a directory, not a " + std::string(what) + " file");
    if (written_in_place(path)) return;  // a FIFO may find its reader later
    const fs::path target = rename_target(path);
    if (fs::exists(target, ec) && ::access(target.c_str(), W_OK) != 0)
        throw InputError(path.string() + ": cannot write " + std::string(what) + " (" +
                         std::strerror(errno) + ")");
    fs::path temp;
    const int fd = open_temporary(target, temp);
    if (fd < 0)
        throw InputError(path.string() + ": cannot create " + std::string(what) + " (" +
                         temporary_error(errno) + ")");
    ::close(fd);
    ::unlink(temp.c_str());
}

std::optional<std::string> output_identity(const std::filesystem::path& path) {
    if (written_in_place(path)) return std::nullopt;
    struct stat status {};
    // An existing file is its device and inode (hard links, symbolic links), a new one its
    // resolved path: "d:" and "p:" keep the two kinds apart.
    if (::stat(path.c_str(), &status) == 0)
        return "d:" + std::to_string(status.st_dev) + ":" + std::to_string(status.st_ino);
    std::error_code ec;
    const fs::path resolved = fs::weakly_canonical(fs::absolute(path), ec);
    return "p:" + (ec ? fs::absolute(path).lexically_normal() : resolved).string();
}

bool same_output_file(const std::filesystem::path& a, const std::filesystem::path& b) {
    const std::optional<std::string> ia = output_identity(a);
    return ia && ia == output_identity(b);
}

void check_distinct_files(const std::vector<NamedPath>& outputs,
                          const std::vector<NamedPath>& inputs) {
    // By identity (util/output_file.h), so that thousands of frames cost no pairwise checks.
    std::map<std::string, const NamedPath*> written;
    for (const NamedPath& out : outputs) {
        if (out.path.empty()) continue;
        const std::optional<std::string> id = output_identity(out.path);
        if (!id) continue;
        const auto [at, fresh] = written.emplace(*id, &out);
        if (!fresh)
            throw InputError(at->second->option + " and " + out.option + " both name " +
                             at->second->path + ": give each output a file of its own");
    }
    for (const NamedPath& in : inputs) {
        if (in.path.empty() || in.path.starts_with("builtin:")) continue;
        const std::optional<std::string> id = output_identity(in.path);
        if (!id) continue;
        if (const auto at = written.find(*id); at != written.end())
            throw InputError(at->second->option + " " + at->second->path + " is the " + in.option +
                             " input" + (in.path == at->second->path ? "" : " " + in.path) +
                             ": writing it would replace what is read");
    }
}

void create_parent_folders(const std::filesystem::path& file) {
    if (!file.has_parent_path()) return;
    const std::filesystem::path folder = file.parent_path();
    std::error_code error;
    std::filesystem::create_directories(folder, error);
    if (!error && ::access(folder.c_str(), W_OK) != 0) error.assign(errno, std::generic_category());
    if (error)
        throw InputError(file.string() + ": cannot write to the folder " + folder.string() + " (" +
                         error.message() + ")");
}

}  // namespace edacrt
