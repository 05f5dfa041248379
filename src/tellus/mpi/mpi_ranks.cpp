#include "tellus/mpi/mpi_ranks.hpp"

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
    // Only the main thread calls MPI; oneTBB's workers never do.
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
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

 private:
  int rank_ = 0, size_ = 1;
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
