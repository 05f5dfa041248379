#pragma once
// Replacing some columns of a column-major layer array in place (an edit of material stacks):
// the arrays are `layers` and `offsets` (column c's layers are [offsets[c], offsets[c + 1]),
// offsets.back() == layers.size()). The columns between the replaced runs move as blocks
// (memmove, no new allocation unless the layers grow past the capacity): an edit costs one
// pass over memory already mapped, not a rebuild of every column. GL-free, header-only (used
// for StackTerrain and QuantisedStacks).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace tellus {

// Columns [firstColumn, firstColumn + counts.size()) replaced: counts[i] layers of `layers`
// (in order) for column firstColumn + i.
template <typename Layer>
struct ColumnRun {
  std::size_t firstColumn = 0;
  std::vector<std::uint32_t> counts;
  std::vector<Layer> layers;
};

// `runs` in ascending column order, not overlapping, inside the arrays (callers check; the
// layer total must stay below 2^32).
template <typename Layer>
void spliceColumns(std::vector<Layer>& layers, std::vector<std::uint32_t>& offsets,
                   const std::vector<ColumnRun<Layer>>& runs) {
  const std::size_t n = runs.size();
  if (n == 0) return;
  const std::size_t oldSize = layers.size();
  // Old bounds of each run and the shift of the block of unchanged columns after it.
  std::vector<std::size_t> oldStart(n), oldEnd(n), columnEnd(n);
  std::vector<std::int64_t> shiftBefore(n), shiftAfter(n);
  std::int64_t total = 0;
  for (std::size_t i = 0; i < n; ++i) {
    columnEnd[i] = runs[i].firstColumn + runs[i].counts.size();
    oldStart[i] = offsets[runs[i].firstColumn];
    oldEnd[i] = offsets[columnEnd[i]];
    shiftBefore[i] = total;
    total += std::int64_t(runs[i].layers.size()) - std::int64_t(oldEnd[i] - oldStart[i]);
    shiftAfter[i] = total;
  }
  const auto blockEnd = [&](std::size_t i) { return i + 1 < n ? oldStart[i + 1] : oldSize; };
  if (total > 0) {
    const std::size_t grown = oldSize + std::size_t(total);
    if (layers.capacity() < grown) layers.reserve(grown + grown / 16);  // room for later edits
    layers.resize(grown);
  }
  // Blocks moving left in ascending order, then blocks moving right in descending order: no
  // block is overwritten before it has moved (every block's destination lies beyond the final
  // place of the blocks before it, which is where the unmoved ones still are).
  const auto at = [&](std::size_t index) { return layers.begin() + std::ptrdiff_t(index); };
  for (std::size_t i = 0; i < n; ++i) {
    if (shiftAfter[i] >= 0) continue;
    std::move(at(oldEnd[i]), at(blockEnd(i)), at(std::size_t(std::int64_t(oldEnd[i]) + shiftAfter[i])));
  }
  for (std::size_t i = n; i-- > 0;) {
    if (shiftAfter[i] <= 0) continue;
    std::move_backward(at(oldEnd[i]), at(blockEnd(i)),
                       at(std::size_t(std::int64_t(blockEnd(i)) + shiftAfter[i])));
  }
  // The runs' new layers in their final places, and the offsets.
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t start = std::size_t(std::int64_t(oldStart[i]) + shiftBefore[i]);
    std::copy(runs[i].layers.begin(), runs[i].layers.end(), at(start));
    const std::size_t lastOffset = i + 1 < n ? runs[i + 1].firstColumn : offsets.size() - 1;
    for (std::size_t c = columnEnd[i]; c <= lastOffset; ++c) {
      offsets[c] = std::uint32_t(std::int64_t(offsets[c]) + shiftAfter[i]);
    }
    std::size_t offset = start;
    for (std::size_t j = 0; j < runs[i].counts.size(); ++j) {
      offsets[runs[i].firstColumn + j] = std::uint32_t(offset);
      offset += runs[i].counts[j];
    }
  }
  if (total < 0) layers.resize(oldSize - std::size_t(-total));
}

}  // namespace tellus
