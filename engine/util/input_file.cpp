#include "util/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <utility>

#include "util/error.h"

namespace edacrt {
namespace {

/// Closes a descriptor on every path out.
struct Descriptor {
    int fd;
    ~Descriptor() {
        if (fd >= 0) ::close(fd);
    }
};

std::string too_large(const std::filesystem::path& path, std::string_view what,
                      const std::string& size, std::uint64_t max_bytes) {
    return path.string() + ": " + std::string(what) + " of " + size + " bytes is larger than the " +
           std::to_string(max_bytes) + " bytes read";
}

/// Opens `path` for reading after checking it is a regular file of at most `max_bytes`.
int open_checked(const std::filesystem::path& path, std::string_view what, std::uint64_t max_bytes,
                 std::uint64_t& size) {
    // O_NONBLOCK: opening a FIFO without a writer would otherwise wait for one.
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0)
        throw InputError(path.string() + ": cannot read " + std::string(what) + " (" +
                         std::strerror(errno) + ")");
    Descriptor guard{fd};
    struct stat status {};
    if (::fstat(fd, &status) != 0)
        throw InputError(path.string() + ": cannot read " + std::string(what) + " (" +
                         std::strerror(errno) + ")");
    if (!S_ISREG(status.st_mode))
        throw InputError(path.string() + ": not a regular file (" +
                         (S_ISDIR(status.st_mode)    ? "a directory"
                          : S_ISFIFO(status.st_mode) ? "a FIFO"
                                                     : "a device or socket") +
                         "); the " + std::string(what) + " must be a file");
    size = std::uint64_t(status.st_size);
    if (size > max_bytes) throw InputError(too_large(path, what, std::to_string(size), max_bytes));
    return std::exchange(guard.fd, -1);
}

}  // namespace

std::uint64_t check_input_file(const std::filesystem::path& path, std::string_view what,
                               std::uint64_t max_bytes) {
    std::uint64_t size = 0;
    ::close(open_checked(path, what, max_bytes, size));
    return size;
}

std::string read_text_file(const std::filesystem::path& path, std::string_view what,
                           std::uint64_t max_bytes) {
    std::uint64_t size = 0;
    const Descriptor file{open_checked(path, what, max_bytes, size)};
    std::string text;
    text.resize(std::size_t(size));
    std::size_t used = 0;
    for (;;) {
        // One byte past the cap tells a file that grew (or a /proc file of size 0) from one
        // that fits.
        if (used == text.size()) {
            if (used > max_bytes)
                throw InputError(
                    too_large(path, what, "more than " + std::to_string(max_bytes), max_bytes));
            text.resize(std::size_t(std::min<std::uint64_t>(max_bytes + 1, used + 65536)));
        }
        const ssize_t n = ::read(file.fd, text.data() + used, text.size() - used);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0)
            throw InputError(path.string() + ": cannot read " + std::string(what) + " (" +
                             std::strerror(errno) + ")");
        if (n == 0) break;
        used += std::size_t(n);
    }
    text.resize(used);
    return text;
}

}  // namespace edacrt
