#include "util/output_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

#include "util/error.h"

namespace edacrt {

OutputFile::OutputFile(const std::filesystem::path& path, std::string what)
    : path_(path), what_(std::move(what)), file_(std::fopen(path.c_str(), "wb")) {
    if (!file_)
        throw InputError(path_.string() + ": cannot create " + what_ + " (" + std::strerror(errno) +
                         ")");
}

OutputFile::~OutputFile() {
    if (file_) std::fclose(file_);
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
    errno = 0;
    if (std::fclose(std::exchange(file_, nullptr)) != 0 && !error_) error_ = errno ? errno : EIO;
    if (error_)
        throw InputError(path_.string() + ": cannot write " + what_ + " (" + std::strerror(error_) +
                         ")");
}

void write_file(const std::filesystem::path& path, std::string_view bytes, std::string what) {
    OutputFile file(path, std::move(what));
    file.write(bytes);
    file.close();
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
