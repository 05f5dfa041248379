#include "tellus/core/mapped_file.hpp"

#include <cerrno>
#include <cstring>
#include <utility>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

namespace tellus {

MappedFile::~MappedFile() {
  if (data_) munmap(const_cast<std::byte*>(data_), size_);
}

MappedFile::MappedFile(MappedFile&& other) noexcept
    : data_(std::exchange(other.data_, nullptr)), size_(std::exchange(other.size_, 0)) {}

MappedFile& MappedFile::operator=(MappedFile&& other) noexcept {
  if (this != &other) {
    if (data_) munmap(const_cast<std::byte*>(data_), size_);
    data_ = std::exchange(other.data_, nullptr);
    size_ = std::exchange(other.size_, 0);
  }
  return *this;
}

Result<MappedFile> MappedFile::open(const std::filesystem::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return makeError("cannot open '{}': {}", path.string(), std::strerror(errno));
  struct stat info {};
  if (fstat(fd, &info) != 0 || !S_ISREG(info.st_mode)) {
    ::close(fd);
    return makeError("'{}' is not a regular file", path.string());
  }
  if (info.st_size == 0) {
    ::close(fd);
    return makeError("'{}' is empty", path.string());
  }
  void* data = mmap(nullptr, std::size_t(info.st_size), PROT_READ, MAP_SHARED, fd, 0);
  const int mapError = errno;
  ::close(fd);  // the mapping keeps the file
  if (data == MAP_FAILED) {
    return makeError("cannot map '{}': {}", path.string(), std::strerror(mapError));
  }
  MappedFile file;
  file.data_ = static_cast<const std::byte*>(data);
  file.size_ = std::size_t(info.st_size);
  return file;
}

}  // namespace tellus
