#pragma once
// The pages of an imagery virtual texture and which of them are resident (GL-free).
//
// A virtual texture is a stack of layers (imagery pyramids, dem/imagery_pyramid.hpp, later ones
// drawn over earlier ones); its pages are the pyramids' tiles, numbered layer by layer, level by
// level (0 = full resolution), row by row: one index space shared by the GPU's page table and
// its feedback (shaders/common/imagery.glsl). A fixed number of slots holds resident pages.
// Each frame the GPU reports the pages it wanted (a frame or more late); the residency wants
// those and their ancestors, loads the coarsest missing first within an upload budget, evicts
// the least recently wanted, and keeps every layer's root (the whole image in one tile) resident
// so that a lookup always finds a page: the page table sends each page to its nearest resident
// ancestor, so the coarser level is shown until the finer one arrives.
#include <cstdint>
#include <span>
#include <vector>

#include "tellus/core/result.hpp"

namespace tellus {

struct ImageryLevelPages {
  int firstPage = 0;  // index of tile (0, 0)
  int tilesX = 0, tilesY = 0;
};

struct ImageryPageKey {
  int layer = 0, level = 0, x = 0, y = 0;
  bool operator==(const ImageryPageKey&) const = default;
};

class ImageryPageLayout {
 public:
  // Appends a layer whose level m has tiles[m] = (tilesX, tilesY); the last level is one tile.
  Status addLayer(std::span<const ImageryLevelPages> levels);
  int layerCount() const { return int(layers_.size()); }
  int levels(int layer) const { return int(layers_[std::size_t(layer)].size()); }
  const ImageryLevelPages& level(int layer, int level) const {
    return layers_[std::size_t(layer)][std::size_t(level)];
  }
  int pageCount() const { return pageCount_; }
  int pageIndex(const ImageryPageKey& key) const;  // -1 outside the layer's level
  ImageryPageKey keyOf(int page) const;
  int parentOf(int page) const;  // -1 for a layer's root
  int rootOf(int layer) const;

 private:
  std::vector<std::vector<ImageryLevelPages>> layers_;
  std::vector<int> layerOfPage_;
  int pageCount_ = 0;
};

// A page table entry: 0 = nothing resident; else slot + 1 in bits 0..15 and the resident
// (ancestor) page's level in bits 16..23.
std::uint32_t imageryPageEntry(int slot, int level);
int imageryEntrySlot(std::uint32_t entry);   // -1 for 0
int imageryEntryLevel(std::uint32_t entry);

struct ImageryUpload {
  int page = 0;
  int slot = 0;
};

// What one update decided.
struct ImageryPlan {
  std::vector<ImageryUpload> uploads;  // coarsest first
  int evictions = 0;
  int pending = 0;      // wanted pages still not resident after the uploads
  int unplaceable = 0;  // wanted pages with no slot: every slot holds a page wanted now
};

class ImageryResidency {
 public:
  // `slots` >= the layers' count (their roots stay resident); `uploadsPerUpdate` >= 1.
  static Result<ImageryResidency> create(ImageryPageLayout layout, int slots, int uploadsPerUpdate);

  const ImageryPageLayout& layout() const { return layout_; }
  int slots() const { return int(slotPage_.size()); }
  int residentCount() const;
  // The pages a frame's lookups asked for (any order; repeats and out-of-range ignored): they
  // and their ancestors become wanted as of `frame` (frames increase).
  void want(std::span<const int> pages, std::uint64_t frame);
  // Chooses this update's uploads (the slots they go to are free once plan() returns: pages
  // evicted for them are no longer resident) and marks them resident: the caller transfers
  // every one before the next draw. Layer roots come first, on the first call, within the
  // budget when it allows (all of them in any case).
  ImageryPlan plan();
  // One entry per page (imageryPageEntry): its own slot when resident, else its nearest
  // resident ancestor's.
  std::vector<std::uint32_t> pageTable() const;
  int slotOf(int page) const { return pageSlot_[std::size_t(page)]; }  // -1 when not resident
  // True while some page wanted at the latest frame is not resident.
  bool anyPending() const;

 private:
  ImageryResidency() = default;
  ImageryPageLayout layout_;
  int uploadsPerUpdate_ = 1;
  std::vector<int> pageSlot_;             // per page: its slot or -1
  std::vector<int> slotPage_;             // per slot: its page or -1
  std::vector<std::uint64_t> wantedAt_;   // per page: the last frame that wanted it (+1; 0 never)
  std::uint64_t latestFrame_ = 0;         // +1 as wantedAt_
  std::vector<int> latestWanted_;         // the pages (with ancestors) the latest frame wanted
};

}  // namespace tellus
