#pragma once
// The processes of one job that work together (MPI's ranks): `mpirun -np N tellus build
// --global ...` starts N copies of the command, and each learns its rank and the others' results
// through this interface. A command run without mpirun is one rank (SingleRank), so the same
// code serves both. The MPI implementation is in tellus/mpi/mpi_ranks.hpp.
//
// Every call here is collective: every rank must make the same calls in the same order, or the
// job waits for ever. Code that can fail between two collectives therefore carries its Status to
// the next agree() instead of returning early on its own.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "tellus/core/result.hpp"

namespace tellus {

class Ranks {
 public:
  virtual ~Ranks() = default;
  virtual int rank() const = 0;  // 0 .. size() - 1
  virtual int size() const = 0;
  // Every rank gives its bytes (any size, up to 2 GiB); every rank receives all of them, in
  // rank order.
  virtual Result<std::vector<std::vector<std::byte>>> allGather(std::span<const std::byte> local) = 0;

  // Progress of a long step, point to point rather than collective, so that rank 0 can show one
  // bar for the whole job. Ranks other than 0 send their count of work done now and then, from
  // any one thread at a time, and `last` once at the end of the step. On rank 0,
  // progressOfOthers() takes what has arrived, without waiting: the sum of the latest counts,
  // and whether every other rank has sent its last count of the step. Rank 0 ends the step by
  // calling it with `endingStep` until allLast: that call resets the marks for the next step
  // (calls without it, during the step, leave them).
  struct OthersProgress {
    std::uint64_t done = 0;
    bool allLast = false;
  };
  virtual void sendProgress(std::uint64_t done, bool last) = 0;
  virtual OthersProgress progressOfOthers(bool endingStep) = 0;
};

// The whole job is this process.
class SingleRank final : public Ranks {
 public:
  int rank() const override { return 0; }
  int size() const override { return 1; }
  Result<std::vector<std::vector<std::byte>>> allGather(std::span<const std::byte> local) override {
    return std::vector<std::vector<std::byte>>{std::vector<std::byte>(local.begin(), local.end())};
  }
  void sendProgress(std::uint64_t, bool) override {}
  OthersProgress progressOfOthers(bool) override { return {0, true}; }
};

// Collective: succeeds on every rank when `local` succeeded on every rank. Otherwise every rank
// fails: a rank that failed with its own error, the others with "rank K: <K's error>" of the
// first rank that failed.
Status agree(Ranks& ranks, const Status& local);

// Collective: the values of every rank, concatenated in rank order.
template <typename T>
Result<std::vector<T>> allGatherValues(Ranks& ranks, std::span<const T> local) {
  static_assert(std::is_trivially_copyable_v<T>);
  Result<std::vector<std::vector<std::byte>>> parts = ranks.allGather(std::as_bytes(local));
  if (!parts) return parts.error();
  std::vector<T> all;
  for (const std::vector<std::byte>& part : parts.value()) {
    const std::size_t first = all.size();
    all.resize(first + part.size() / sizeof(T));
    if (!part.empty()) std::memcpy(all.data() + first, part.data(), part.size());
  }
  return all;
}

}  // namespace tellus
