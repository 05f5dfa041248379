#pragma once
// Ranks (tellus/core/ranks.hpp) over MPI, for commands started by `mpirun -np N tellus ...`
// (Open MPI from Debian's packages; any MPI with the standard C API builds it).
#include <memory>

#include "tellus/core/ranks.hpp"

namespace tellus {

// True when this process was started by an MPI launcher (mpirun, mpiexec, srun): its
// environment names a rank.
bool launchedByMpi();

// The ranks of this job: MPI's world when launchedByMpi() (MPI is initialised here and finalised
// when the returned object is destroyed; call once), else a SingleRank, so that a command run
// without mpirun runs as it always has and never starts MPI. Errors when launched by mpirun but
// built without MPI.
Result<std::unique_ptr<Ranks>> openRanks();

}  // namespace tellus
