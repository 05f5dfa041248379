#include "tellus/tiles/payload_spool.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <vector>

namespace tellus {
namespace fs = std::filesystem;

Status writeAllAt(int fd, std::span<const std::byte> data, std::uint64_t offset,
                  const std::string& name) {
  while (!data.empty()) {
    const ssize_t n = ::pwrite(fd, data.data(), data.size(), off_t(offset));
    if (n < 0) {
      if (errno == EINTR) continue;
      return makeError("cannot write '{}': {}", name, std::strerror(errno));
    }
    data = data.subspan(std::size_t(n));
    offset += std::uint64_t(n);
  }
  return {};
}

Result<std::unique_ptr<PayloadSpool>> PayloadSpool::create(const fs::path& parent) {
  Result<ScratchFolder> folder = ScratchFolder::create(parent);
  if (!folder) return folder.error();
  fs::path path = folder->path() / "payloads.spool";
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (fd < 0) return makeError("cannot create '{}': {}", path.string(), std::strerror(errno));
  return std::unique_ptr<PayloadSpool>(
      new PayloadSpool(std::move(folder.value()), std::move(path), fd));
}

PayloadSpool::~PayloadSpool() {
  if (fd_ >= 0) ::close(fd_);
}

Result<std::uint64_t> PayloadSpool::append(std::span<const std::byte> payload) {
  std::lock_guard lock(mutex_);
  const std::uint64_t at = end_;
  if (Status s = writeAllAt(fd_, payload, at, path_.string()); !s) return s.error();
  end_ += payload.size();
  return at;
}

Status PayloadSpool::copyTo(std::uint64_t from, std::uint64_t bytes, int destination,
                            std::uint64_t to, const std::string& destinationName) const {
  std::vector<std::byte> buffer(std::min<std::uint64_t>(bytes, std::uint64_t(4) << 20));
  while (bytes > 0) {
    const std::size_t chunk = std::size_t(std::min<std::uint64_t>(bytes, buffer.size()));
    const ssize_t n = ::pread(fd_, buffer.data(), chunk, off_t(from));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      return makeError("cannot read '{}': {}", path_.string(),
                       n < 0 ? std::strerror(errno) : "it is shorter than written");
    }
    if (Status s = writeAllAt(destination, std::span(buffer.data(), std::size_t(n)), to,
                              destinationName);
        !s) {
      return s;
    }
    from += std::uint64_t(n);
    to += std::uint64_t(n);
    bytes -= std::uint64_t(n);
  }
  return {};
}

}  // namespace tellus
