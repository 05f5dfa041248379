#include "tellus/tiles/byte_source.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>

#include "tellus/core/input_file.hpp"
#include "tellus/tiles/http_byte_source.hpp"
#include "tellus/tiles/store_container.hpp"

namespace tellus {
namespace {

class FileByteSource final : public ByteSource {
 public:
  FileByteSource(int fd, std::uint64_t size, std::string name)
      : fd_(fd), size_(size), name_(std::move(name)) {}
  ~FileByteSource() override { ::close(fd_); }
  Status readAt(void* data, std::size_t bytes, std::uint64_t offset) const override {
    return preadExact(fd_, data, bytes, offset);
  }
  std::uint64_t size() const override { return size_; }
  const std::string& name() const override { return name_; }

 private:
  int fd_;
  std::uint64_t size_;
  std::string name_;
};

}  // namespace

bool isUrl(std::string_view location) {
  auto startsWith = [&](std::string_view prefix) {
    return location.size() > prefix.size() &&
           std::equal(prefix.begin(), prefix.end(), location.begin(),
                      [](char a, char b) { return a == std::tolower(static_cast<unsigned char>(b)); });
  };
  return startsWith("http://") || startsWith("https://");
}

Result<std::shared_ptr<ByteSource>> openByteSource(const std::string& location) {
  if (isUrl(location)) {
    Result<std::shared_ptr<HttpByteSource>> http = HttpByteSource::open(location);
    if (!http) return http.error();
    return std::shared_ptr<ByteSource>(std::move(http.value()));
  }
  Result<int> fd = openRegularInput(location);  // a FIFO is refused, never waited on
  if (!fd) return fd.error();
  struct stat info {};
  if (::fstat(fd.value(), &info) != 0) {
    const int error = errno;
    ::close(fd.value());
    return makeError("cannot open '{}': {}", location, std::strerror(error));
  }
  return std::shared_ptr<ByteSource>(
      std::make_shared<FileByteSource>(fd.value(), std::uint64_t(info.st_size), location));
}

}  // namespace tellus
