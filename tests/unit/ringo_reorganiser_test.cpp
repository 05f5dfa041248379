// RINGO's reorganisation off the render thread (seed 002): after any sequence of moves the
// blocks the render thread collected equal blocks loaded fresh where the matrix ended, coarser
// blocks are derived rather than reloaded, a slow store never holds up submit() or takeReady(),
// the upload budget is respected, and a failed load is reported while the rest go on.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>
#include <map>
#include <random>

#include "ringo_test_heights.hpp"
#include "tellus/lod/ringo/ringo_reorganiser.hpp"

namespace tellus {
namespace {

constexpr RingoLayout kLayout{.rings = 4, .tileCells = 16};

std::vector<float> syntheticBlock(const RingoBlock& block) {
  return test::ringoTestHeights(block, kLayout, 0.0, 10007);
}

// The render thread's view: what each slot draws, and the last move a block came from (blocks
// come move by move, oldest first).
struct Drawn {
  std::map<int, RingoReadyBlock> slots;
  std::uint64_t lastMove = 0;
};
void collect(RingoReorganiser& reorganiser, Drawn& drawn, std::size_t budget) {
  for (RingoReadyBlock& ready : reorganiser.takeReady(budget)) {
    EXPECT_LE(drawn.slots.size(), std::size_t(kLayout.side() * kLayout.side()));
    EXPECT_FALSE(ready.failed);
    EXPECT_GE(ready.move, drawn.lastMove);
    drawn.lastMove = ready.move;
    drawn.slots[ready.slot] = std::move(ready);
  }
}

TEST(RingoReorganiser, CollectedBlocksEqualFreshLoadsAfterAnySequenceOfMoves) {
  std::atomic<int> loads{0};
  RingoBlockMatrix matrix(kLayout, 7, 100, 40);
  RingoReorganiser reorganiser(kLayout, matrix.slotCount(), [&](const RingoBlock& block) {
    ++loads;
    return Result<std::vector<float>>(syntheticBlock(block));
  });
  reorganiser.submit(ringoInitialUpdates(matrix));
  Drawn drawn;
  std::mt19937 random(3);
  std::uniform_int_distribution<int> step(-1, 1);
  std::int64_t x = 100;
  int y = 40;
  std::size_t moves = 1;
  for (int move = 0; move < 200; ++move) {
    x += step(random);
    y += step(random);
    std::vector<RingoBlockUpdate> updates = matrix.recentre(x, y);
    moves += updates.empty() ? 0 : 1;  // standing still changes nothing
    reorganiser.submit(std::move(updates));
    collect(reorganiser, drawn, 7);  // a frame's upload budget
  }
  reorganiser.waitIdle();
  while (!reorganiser.idle()) collect(reorganiser, drawn, 7);
  ASSERT_FALSE(reorganiser.lastError());
  for (int slot = 0; slot < matrix.slotCount(); ++slot) {
    const RingoBlock& wanted = matrix.slot(slot);
    ASSERT_TRUE(drawn.slots.count(slot)) << slot;
    EXPECT_EQ(drawn.slots[slot].block, wanted) << slot;
    EXPECT_EQ(drawn.slots[slot].heights, syntheticBlock(wanted)) << slot;
  }
  const RingoReorganiserStats stats = reorganiser.stats();
  EXPECT_EQ(stats.moves, moves);
  EXPECT_GT(stats.derived, 0u);  // "D" blocks came from their own finer heights
  EXPECT_EQ(stats.loaded, std::size_t(loads.load()));
}

TEST(RingoReorganiser, ASlowStoreNeverHoldsUpTheRenderThread) {
  std::promise<void> release;
  std::shared_future<void> gate = release.get_future().share();
  std::atomic<bool> submitted{false}, loadedBeforeSubmitReturned{false};
  RingoBlockMatrix matrix(kLayout, 7, 10, 10);
  RingoReorganiser reorganiser(kLayout, matrix.slotCount(), [&](const RingoBlock& block) {
    // The store answers only when the test lets it (or after 20 s, a failure below).
    if (gate.wait_for(std::chrono::seconds(20)) != std::future_status::ready || !submitted) {
      loadedBeforeSubmitReturned = true;
    }
    return Result<std::vector<float>>(syntheticBlock(block));
  });
  std::vector<RingoBlockUpdate> first = ringoInitialUpdates(matrix);
  std::vector<RingoBlockUpdate> second = matrix.recentre(11, 10);
  const std::size_t updates = first.size() + second.size();
  reorganiser.submit(std::move(first));
  reorganiser.submit(std::move(second));
  submitted = true;
  // While the store is stuck: frames go on, nothing is ready, nothing is idle.
  for (int frame = 0; frame < 3; ++frame) EXPECT_TRUE(reorganiser.takeReady(64).empty());
  EXPECT_FALSE(reorganiser.idle());
  release.set_value();
  reorganiser.waitIdle();
  EXPECT_FALSE(loadedBeforeSubmitReturned);
  std::size_t collected = 0;
  while (!reorganiser.idle()) {
    const std::size_t taken = reorganiser.takeReady(16).size();
    EXPECT_LE(taken, 16u);  // the budget
    collected += taken;
  }
  EXPECT_EQ(collected, updates);  // every update of both moves, once
}

TEST(RingoReorganiser, AFailedLoadIsReportedAndTheOtherBlocksArrive) {
  RingoBlockMatrix matrix(kLayout, 7, 50, 20);
  const GeoTileKey broken = matrix.at(2, -3).key;
  RingoReorganiser reorganiser(kLayout, matrix.slotCount(), [&](const RingoBlock& block) {
    if (block.key == broken) return Result<std::vector<float>>(makeError("tile {} is corrupt", block.key.x));
    return Result<std::vector<float>>(syntheticBlock(block));
  });
  reorganiser.submit(ringoInitialUpdates(matrix));
  reorganiser.waitIdle();
  ASSERT_TRUE(reorganiser.lastError());
  EXPECT_NE(reorganiser.lastError()->message.find("is corrupt"), std::string::npos);
  // Every update comes back, the failed one marked (the slot keeps what it drew).
  const std::vector<RingoReadyBlock> ready = reorganiser.takeReady(1000);
  EXPECT_EQ(ready.size(), std::size_t(matrix.slotCount()));
  EXPECT_EQ(std::count_if(ready.begin(), ready.end(), [](const auto& r) { return r.failed; }), 1);
  EXPECT_EQ(reorganiser.stats().failures, 1u);
}

}  // namespace
}  // namespace tellus
