#pragma once
// RINGO (seed 002): the reorganisation of the block matrix, off the render thread. GL-free.
//
// When the viewer crosses the border of the central block, RingoBlockMatrix::recentre() lists
// the slots that change; submit() hands them to oneTBB worker threads and returns at once. A
// move's lanes (matrix columns for a move north or south, rows for east or west) run as
// parallel tasks, the seed's Figure 4; each rebuilds its slots one after the other: a coarser
// block ("D") from the slot's own finer heights, a new or finer one ("R") through the loader.
// Moves run in the order they were submitted, so a derived block always reads the heights the
// previous move left in its slot. The render thread collects finished blocks with takeReady(),
// as many per frame as its upload budget allows, and keeps drawing the blocks it has until
// their replacements arrive: no frame waits for the reorganisation. Every update of a move
// comes back exactly once (a failed load too, marked), tagged with its move, so that the render
// thread can show a move whole: half a move could put blocks two levels apart side by side.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include "tellus/core/result.hpp"
#include "tellus/dem/geoid.hpp"
#include "tellus/lod/ringo/ringo_block_matrix.hpp"
#include "tellus/lod/ringo/ringo_block_mesh.hpp"
#include "tellus/lod/ringo/ringo_morph.hpp"

namespace tellus {

// Reads a block's heights ((cells + 1)^2 samples; loadRingoBlock in the renderer, a slow fake
// in tests). Called on worker threads, several at once.
using RingoBlockLoader = std::function<Result<std::vector<float>>(const RingoBlock&)>;

// A rebuilt slot for the render thread: its block, heights and mesh, built on the worker (none
// when the block does not exist: the slot is to be emptied).
struct RingoReadyBlock {
  std::uint64_t move = 0;  // submit()'s number for its move
  int slot = 0;
  bool failed = false;     // the load failed: the slot keeps what it has (lastError() says why)
  RingoBlock block;
  std::vector<float> heights;
  RingoBlockMesh mesh;
};

struct RingoReorganiserStats {
  std::size_t moves = 0;          // moves completed
  std::size_t loaded = 0;         // blocks read through the loader
  std::size_t derived = 0;        // blocks coarsened from their own heights
  std::size_t failures = 0;       // loads that failed (lastError() says why)
  double workerCpuSeconds = 0.0;  // CPU time of the lanes' tasks, summed over the workers
};

// Every existing slot of `matrix` as a block to load: what a fresh matrix needs.
std::vector<RingoBlockUpdate> ringoInitialUpdates(const RingoBlockMatrix& matrix);

class RingoReorganiser {
 public:
  // `geoid` (may be null: heights taken as ellipsoidal) places the meshes' vertices; it must
  // outlive the reorganiser. `threads`: the most worker threads a move uses (0: oneTBB's
  // default, every core).
  RingoReorganiser(RingoLayout layout, int slotCount, RingoBlockLoader loader,
                   const Geoid* geoid = nullptr, int threads = 0);
  ~RingoReorganiser();  // waits for the work in flight; drops what is queued
  RingoReorganiser(const RingoReorganiser&) = delete;
  RingoReorganiser& operator=(const RingoReorganiser&) = delete;

  // Queues one move's updates (from recentre() or ringoInitialUpdates()); returns at once with
  // the move's number (0, 1, 2, ... in submission order; an empty move gets none: -1).
  std::int64_t submit(std::vector<RingoBlockUpdate> updates);
  // Up to `maxBlocks` finished blocks: those of the oldest move first, and within a move the
  // finest (lowest level) first, the blocks near the viewer mattering most.
  std::vector<RingoReadyBlock> takeReady(std::size_t maxBlocks);
  // Nothing queued, running or waiting to be taken.
  bool idle() const;
  // A move is queued or running (the destructor would wait for the running one).
  bool working() const;
  // Drops the queued moves (not the running one): the matrix is being abandoned.
  void cancelQueued();
  // Blocks until no move is queued or running (stills, tests).
  void waitIdle();
  std::optional<Error> lastError() const;
  RingoReorganiserStats stats() const;
  // The surface the blocks built from now on morph from (ringo_morph.hpp; null: none, once the
  // matrix has morphed). Blocks being built keep the source they started with.
  void setMorphSource(std::shared_ptr<const RingoMorphSource> source);

 private:
  void startNextMoveLocked();
  void runMove(std::uint64_t move, const std::vector<RingoBlockUpdate>& updates);
  void rebuild(std::uint64_t move, const RingoBlockUpdate& update);

  RingoLayout layout_;
  RingoBlockLoader loader_;
  const Geoid* geoid_;
  // Per slot: the heights the workers last built (touched only by the move running).
  std::vector<std::vector<float>> heights_;
  std::vector<int> heldLevel_;  // their level
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<std::pair<std::uint64_t, std::vector<RingoBlockUpdate>>> moves_;
  std::uint64_t submitted_ = 0;
  bool running_ = false;
  std::deque<RingoReadyBlock> ready_;
  RingoReorganiserStats stats_;
  std::optional<Error> lastError_;
  std::shared_ptr<const RingoMorphSource> morphSource_;
  tbb::task_arena arena_;  // the lanes' parallel_for runs here
  tbb::task_group tasks_;
};

}  // namespace tellus
