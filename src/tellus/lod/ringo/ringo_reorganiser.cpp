#include "tellus/lod/ringo/ringo_reorganiser.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <map>

#include "tellus/core/thread_cpu_clock.hpp"
#include "tellus/lod/ringo/ringo_block_data.hpp"

namespace tellus {

std::vector<RingoBlockUpdate> ringoInitialUpdates(const RingoBlockMatrix& matrix) {
  std::vector<RingoBlockUpdate> updates;
  const int side = matrix.layout().side();
  for (int slot = 0; slot < matrix.slotCount(); ++slot) {
    if (!matrix.slot(slot).exists) continue;
    updates.push_back({slot, slot % side, matrix.slot(slot), RingoBlockSource::Reloaded, 0});
  }
  return updates;
}

RingoReorganiser::RingoReorganiser(RingoLayout layout, int slotCount, RingoBlockLoader loader,
                                   const Geoid* geoid, int threads)
    : layout_(layout),
      loader_(std::move(loader)),
      geoid_(geoid),
      heights_(std::size_t(slotCount)),
      heldLevel_(std::size_t(slotCount), 0),
      arena_(threads > 0 ? threads : int(tbb::task_arena::automatic)) {}

RingoReorganiser::~RingoReorganiser() {
  {
    std::lock_guard lock(mutex_);
    moves_.clear();
  }
  tasks_.wait();
}

std::int64_t RingoReorganiser::submit(std::vector<RingoBlockUpdate> updates) {
  if (updates.empty()) return -1;
  std::lock_guard lock(mutex_);
  const std::uint64_t move = submitted_++;
  moves_.emplace_back(move, std::move(updates));
  startNextMoveLocked();
  return std::int64_t(move);
}

void RingoReorganiser::startNextMoveLocked() {
  if (running_ || moves_.empty()) return;
  running_ = true;
  auto move = std::make_shared<std::pair<std::uint64_t, std::vector<RingoBlockUpdate>>>(
      std::move(moves_.front()));
  moves_.pop_front();
  tasks_.run([this, move] {
    runMove(move->first, move->second);
    std::lock_guard lock(mutex_);
    ++stats_.moves;
    running_ = false;
    startNextMoveLocked();
    changed_.notify_all();
  });
}

void RingoReorganiser::runMove(std::uint64_t move, const std::vector<RingoBlockUpdate>& updates) {
  std::map<int, std::vector<const RingoBlockUpdate*>> lanes;
  for (const RingoBlockUpdate& update : updates) lanes[update.lane].push_back(&update);
  std::vector<const std::vector<const RingoBlockUpdate*>*> work;
  for (const auto& [lane, list] : lanes) work.push_back(&list);
  arena_.execute([&] { tbb::parallel_for(std::size_t(0), work.size(), [&](std::size_t i) {
    const double start = threadCpuSeconds();  // a lane runs on one thread
    for (const RingoBlockUpdate* update : *work[i]) rebuild(move, *update);
    const double seconds = threadCpuSeconds() - start;
    std::lock_guard lock(mutex_);
    stats_.workerCpuSeconds += seconds;
  }); });
}

void RingoReorganiser::rebuild(std::uint64_t move, const RingoBlockUpdate& update) {
  const std::size_t slot = std::size_t(update.slot);
  RingoReadyBlock ready;
  ready.move = move;
  ready.slot = update.slot;
  ready.block = update.block;
  bool derived = false, failed = false;
  std::optional<Error> error;
  if (!update.block.exists) {
    heights_[slot].clear();
  } else if (update.source == RingoBlockSource::Derived && !heights_[slot].empty() &&
             heldLevel_[slot] < update.block.level) {
    heights_[slot] = coarsenRingoBlock(heights_[slot], layout_.cellsAt(heldLevel_[slot]),
                                       update.block.level - heldLevel_[slot]);
    derived = true;
  } else {
    // Reloaded, or derived from a slot whose finer heights failed to load.
    Result<std::vector<float>> loaded = loader_(update.block);
    if (loaded) {
      heights_[slot] = std::move(loaded.value());
    } else {
      heights_[slot].clear();
      failed = true;
      error = loaded.error();
    }
  }
  heldLevel_[slot] = update.block.level;
  ready.heights = heights_[slot];
  if (update.block.exists && !failed) {
    std::shared_ptr<const RingoMorphSource> morphFrom;
    {
      std::lock_guard lock(mutex_);
      morphFrom = morphSource_;
    }
    ready.mesh = buildRingoBlockMesh(update.block, layout_.cellsAt(update.block.level),
                                     ready.heights, geoid_, morphFrom.get());
  }
  std::lock_guard lock(mutex_);
  if (failed) {
    ++stats_.failures;
    lastError_ = error;
    ready.failed = true;  // the render thread keeps what it draws there
    ready.heights.clear();
  } else {
    ++(derived ? stats_.derived : stats_.loaded);
  }
  ready_.push_back(std::move(ready));
}

std::vector<RingoReadyBlock> RingoReorganiser::takeReady(std::size_t maxBlocks) {
  std::lock_guard lock(mutex_);
  std::vector<RingoReadyBlock> taken;
  while (!ready_.empty() && taken.size() < maxBlocks) {
    const auto finest = std::min_element(
        ready_.begin(), ready_.end(), [](const RingoReadyBlock& a, const RingoReadyBlock& b) {
          return std::pair(a.move, a.block.level) < std::pair(b.move, b.block.level);
        });
    taken.push_back(std::move(*finest));
    ready_.erase(finest);
  }
  if (!taken.empty()) changed_.notify_all();
  return taken;
}

bool RingoReorganiser::idle() const {
  std::lock_guard lock(mutex_);
  return !running_ && moves_.empty() && ready_.empty();
}

bool RingoReorganiser::working() const {
  std::lock_guard lock(mutex_);
  return running_ || !moves_.empty();
}

void RingoReorganiser::cancelQueued() {
  std::lock_guard lock(mutex_);
  moves_.clear();
}

void RingoReorganiser::waitIdle() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [this] { return !running_ && moves_.empty(); });
}

std::optional<Error> RingoReorganiser::lastError() const {
  std::lock_guard lock(mutex_);
  return lastError_;
}

void RingoReorganiser::setMorphSource(std::shared_ptr<const RingoMorphSource> source) {
  std::lock_guard lock(mutex_);
  morphSource_ = std::move(source);
}

RingoReorganiserStats RingoReorganiser::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

}  // namespace tellus
