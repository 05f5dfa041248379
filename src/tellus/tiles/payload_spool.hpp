#pragma once
// A file that collects tile payloads in the order they are finished (any order, from any
// thread), to be copied later into their final places in a store: the sharded global build
// (global_store_builder.hpp) finishes tiles in whatever order its threads do, but lays them out
// in one canonical order so that the store's bytes do not depend on the threads or the ranks.
// The file lives in a private scratch folder and is removed with it. Each rank's spool belongs in
// node-local space (the system's temporary folder, $TMPDIR): a scratch folder created in a folder
// that ranks on other machines share would sweep their files as those of dead processes (their
// process ids mean nothing here).
#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <span>

#include "tellus/core/result.hpp"
#include "tellus/core/scratch_folder.hpp"

namespace tellus {

class PayloadSpool {
 public:
  // In a new scratch folder inside `parent` (the system's temporary folder when empty).
  static Result<std::unique_ptr<PayloadSpool>> create(const std::filesystem::path& parent = {});
  ~PayloadSpool();
  PayloadSpool(const PayloadSpool&) = delete;
  PayloadSpool& operator=(const PayloadSpool&) = delete;

  // Thread-safe. Returns where the payload starts in the spool.
  Result<std::uint64_t> append(std::span<const std::byte> payload);
  // Copies `bytes` bytes from spool offset `from` to offset `to` of the open file `destination`
  // (named `destinationName` in messages).
  Status copyTo(std::uint64_t from, std::uint64_t bytes, int destination, std::uint64_t to,
                const std::string& destinationName) const;
  std::uint64_t bytes() const { return end_; }

 private:
  PayloadSpool(ScratchFolder folder, std::filesystem::path path, int fd)
      : folder_(std::move(folder)), path_(std::move(path)), fd_(fd) {}
  ScratchFolder folder_;
  std::filesystem::path path_;
  int fd_ = -1;
  std::mutex mutex_;
  std::uint64_t end_ = 0;
};

// Writes all of `data` at `offset` of `fd` (pwrite, retried on short writes and EINTR).
Status writeAllAt(int fd, std::span<const std::byte> data, std::uint64_t offset,
                  const std::string& name);

}  // namespace tellus
