#include "tellus/mpi/mpi_ranks.hpp"

#include <algorithm>
#include <cstdlib>
#include <limits>

#ifdef TELLUS_WITH_MPI
#include <mpi.h>
#endif

namespace tellus {

bool launchedByMpi() {
  // Open MPI, PMIx-based launchers (Open MPI 5, Slurm) and MPICH/Hydra set one of these.
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"}) {
    if (std::getenv(name) != nullptr) return true;
  }
  return false;
}

#ifdef TELLUS_WITH_MPI
namespace {

class MpiRanks final : public Ranks {
 public:
  MpiRanks() {
    int provided = 0;
    // One thread at a time calls MPI: the main thread, or the thread that sends progress while
    // the main thread waits for oneTBB's workers (which never call MPI).
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SERIALIZED, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
    latest_.assign(std::size_t(size_), 0);
    last_.assign(std::size_t(size_), false);
  }
  ~MpiRanks() override { MPI_Finalize(); }

  int rank() const override { return rank_; }
  int size() const override { return size_; }

  Result<std::vector<std::vector<std::byte>>> allGather(std::span<const std::byte> local) override {
    if (local.size() > std::size_t(std::numeric_limits<int>::max())) {
      return makeError("internal error: {} bytes to exchange between ranks (at most 2 GiB)",
                       local.size());
    }
    const int mine = int(local.size());
    std::vector<int> counts(std::size_t(size_), 0), offsets(std::size_t(size_), 0);
    if (MPI_Allgather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD) != MPI_SUCCESS) {
      return makeError("MPI_Allgather failed");
    }
    long long total = 0;
    for (int k = 0; k < size_; ++k) {
      offsets[std::size_t(k)] = int(total);
      total += counts[std::size_t(k)];
      if (total > std::numeric_limits<int>::max()) {
        return makeError("internal error: {} bytes to exchange between ranks (at most 2 GiB)", total);
      }
    }
    std::vector<std::byte> all(static_cast<std::size_t>(total));
    if (MPI_Allgatherv(local.data(), mine, MPI_BYTE, all.data(), counts.data(), offsets.data(),
                       MPI_BYTE, MPI_COMM_WORLD) != MPI_SUCCESS) {
      return makeError("MPI_Allgatherv failed");
    }
    std::vector<std::vector<std::byte>> parts(static_cast<std::size_t>(size_));
    for (int k = 0; k < size_; ++k) {
      const auto first = all.begin() + offsets[std::size_t(k)];
      parts[std::size_t(k)].assign(first, first + counts[std::size_t(k)]);
    }
    return parts;
  }

  void sendProgress(std::uint64_t done, bool last) override {
    if (rank_ == 0) return;
    // 16 bytes: sent eagerly, so this does not wait for rank 0.
    const std::uint64_t message[2] = {done, last ? 1u : 0u};
    MPI_Send(message, 2, MPI_UINT64_T, 0, kProgressTag, MPI_COMM_WORLD);
  }

  OthersProgress progressOfOthers(bool endingStep) override {
    if (rank_ != 0) return {0, true};
    for (;;) {  // everything already here
      int waiting = 0;
      MPI_Status status;
      MPI_Iprobe(MPI_ANY_SOURCE, kProgressTag, MPI_COMM_WORLD, &waiting, &status);
      if (!waiting) break;
      std::uint64_t message[2] = {0, 0};
      MPI_Recv(message, 2, MPI_UINT64_T, status.MPI_SOURCE, kProgressTag, MPI_COMM_WORLD,
               MPI_STATUS_IGNORE);
      latest_[std::size_t(status.MPI_SOURCE)] = message[0];
      if (message[1] != 0) last_[std::size_t(status.MPI_SOURCE)] = true;
    }
    OthersProgress progress;
    progress.allLast = std::all_of(last_.begin() + 1, last_.end(), [](bool b) { return b; });
    for (int k = 1; k < size_; ++k) progress.done += latest_[std::size_t(k)];
    // The next step starts afresh, but only once this one is ended: a last count that arrives
    // while rank 0 still works must still be there when it ends the step.
    if (progress.allLast && endingStep) std::fill(last_.begin(), last_.end(), false);
    return progress;
  }

 private:
  static constexpr int kProgressTag = 47;
  int rank_ = 0, size_ = 1;
  std::vector<std::uint64_t> latest_;
  std::vector<bool> last_;
};

}  // namespace
#endif

Result<std::unique_ptr<Ranks>> openRanks() {
  if (!launchedByMpi()) return std::unique_ptr<Ranks>(std::make_unique<SingleRank>());
#ifdef TELLUS_WITH_MPI
  return std::unique_ptr<Ranks>(std::make_unique<MpiRanks>());
#else
  return makeError("this tellus was built without MPI, but mpirun started it: rebuild with "
                   "Open MPI's development files (libopenmpi-dev) installed");
#endif
}

}  // namespace tellus
