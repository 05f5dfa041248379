#include "tellus/lod/imagery/imagery_pages.hpp"

#include <algorithm>

namespace tellus {

Status ImageryPageLayout::addLayer(std::span<const ImageryLevelPages> levels) {
  if (levels.empty()) return makeError("an imagery layer needs at least one level");
  if (levels.size() > 16) return makeError("an imagery layer of {} levels: at most 16", levels.size());
  if (levels.back().tilesX != 1 || levels.back().tilesY != 1) {
    return makeError("an imagery layer's last level must be one tile");
  }
  std::vector<ImageryLevelPages> placed;
  for (const ImageryLevelPages& l : levels) {
    if (l.tilesX < 1 || l.tilesY < 1) return makeError("an imagery level without tiles");
    const std::int64_t total = std::int64_t(pageCount_) + std::int64_t(l.tilesX) * l.tilesY;
    if (total > (1 << 24)) return makeError("an imagery virtual texture of more than 2^24 pages");
    placed.push_back({pageCount_, l.tilesX, l.tilesY});
    layerOfPage_.insert(layerOfPage_.end(), std::size_t(l.tilesX) * std::size_t(l.tilesY),
                        int(layers_.size()));
    pageCount_ = int(total);
  }
  layers_.push_back(std::move(placed));
  return {};
}

int ImageryPageLayout::pageIndex(const ImageryPageKey& key) const {
  if (key.layer < 0 || key.layer >= layerCount() || key.level < 0 || key.level >= levels(key.layer)) {
    return -1;
  }
  const ImageryLevelPages& l = level(key.layer, key.level);
  if (key.x < 0 || key.y < 0 || key.x >= l.tilesX || key.y >= l.tilesY) return -1;
  return l.firstPage + key.y * l.tilesX + key.x;
}

ImageryPageKey ImageryPageLayout::keyOf(int page) const {
  const int layer = layerOfPage_[std::size_t(page)];
  const std::vector<ImageryLevelPages>& levels = layers_[std::size_t(layer)];
  int m = int(levels.size()) - 1;
  while (levels[std::size_t(m)].firstPage > page) --m;
  const ImageryLevelPages& l = levels[std::size_t(m)];
  const int local = page - l.firstPage;
  return {layer, m, local % l.tilesX, local / l.tilesX};
}

int ImageryPageLayout::parentOf(int page) const {
  const ImageryPageKey key = keyOf(page);
  if (key.level + 1 >= levels(key.layer)) return -1;
  return pageIndex({key.layer, key.level + 1, key.x / 2, key.y / 2});
}

int ImageryPageLayout::rootOf(int layer) const {
  return layers_[std::size_t(layer)].back().firstPage;
}

std::uint32_t imageryPageEntry(int slot, int level) {
  return std::uint32_t(slot + 1) | (std::uint32_t(level) << 16);
}
int imageryEntrySlot(std::uint32_t entry) { return int(entry & 0xFFFFu) - 1; }
int imageryEntryLevel(std::uint32_t entry) { return int((entry >> 16) & 0xFFu); }

Result<ImageryResidency> ImageryResidency::create(ImageryPageLayout layout, int slots,
                                                  int uploadsPerUpdate) {
  if (layout.layerCount() < 1) return makeError("imagery without layers");
  if (slots < layout.layerCount() || slots > 65535) {
    return makeError("{} imagery slots for {} layers: needs one a layer, at most 65535", slots,
                     layout.layerCount());
  }
  if (uploadsPerUpdate < 1) return makeError("an imagery upload budget of {} pages a frame", uploadsPerUpdate);
  ImageryResidency r;
  r.uploadsPerUpdate_ = uploadsPerUpdate;
  r.pageSlot_.assign(std::size_t(layout.pageCount()), -1);
  r.wantedAt_.assign(std::size_t(layout.pageCount()), 0);
  r.slotPage_.assign(std::size_t(slots), -1);
  r.layout_ = std::move(layout);
  return r;
}

int ImageryResidency::residentCount() const {
  return int(std::count_if(slotPage_.begin(), slotPage_.end(), [](int p) { return p >= 0; }));
}

void ImageryResidency::want(std::span<const int> pages, std::uint64_t frame) {
  const std::uint64_t stamp = frame + 1;
  if (stamp < latestFrame_) return;  // an older frame's report: the newer one decides
  if (stamp > latestFrame_) {
    latestFrame_ = stamp;
    latestWanted_.clear();
  }
  for (int page : pages) {
    // Up the chain until a page already wanted at this frame (its ancestors are, too).
    for (int p = page; p >= 0 && p < layout_.pageCount() && wantedAt_[std::size_t(p)] != stamp;
         p = layout_.parentOf(p)) {
      wantedAt_[std::size_t(p)] = stamp;
      latestWanted_.push_back(p);
    }
  }
}

ImageryPlan ImageryResidency::plan() {
  ImageryPlan plan;
  // The roots, once: lookups always find a page.
  for (int layer = 0; layer < layout_.layerCount(); ++layer) {
    const int root = layout_.rootOf(layer);
    if (pageSlot_[std::size_t(root)] >= 0) continue;
    const auto free = std::find(slotPage_.begin(), slotPage_.end(), -1);
    const int slot = int(free - slotPage_.begin());
    slotPage_[std::size_t(slot)] = root;
    pageSlot_[std::size_t(root)] = slot;
    plan.uploads.push_back({root, slot});
  }
  int budget = std::max(0, uploadsPerUpdate_ - int(plan.uploads.size()));
  std::vector<int> missing;
  for (int page : latestWanted_) {
    if (pageSlot_[std::size_t(page)] < 0) missing.push_back(page);
  }
  // Coarsest first (a finer page is of no use before its parent is shown), then by index.
  std::sort(missing.begin(), missing.end(), [&](int a, int b) {
    const int la = layout_.keyOf(a).level, lb = layout_.keyOf(b).level;
    return la != lb ? la > lb : a < b;
  });
  for (int page : missing) {
    if (budget == 0) {
      ++plan.pending;
      continue;
    }
    // A free slot, else the least recently wanted page that the latest frame did not want
    // (among equals the finest: its ancestors stay).
    int slot = -1;
    std::uint64_t oldest = latestFrame_;
    int oldestLevel = -1;
    for (int s = 0; s < slots(); ++s) {
      const int resident = slotPage_[std::size_t(s)];
      if (resident < 0) {
        slot = s;
        oldestLevel = 1 << 20;
        break;
      }
      const std::uint64_t at = wantedAt_[std::size_t(resident)];
      if (at >= latestFrame_ || layout_.parentOf(resident) < 0) continue;  // wanted now, or a root
      const int level = layout_.keyOf(resident).level;
      if (at < oldest || (at == oldest && level < oldestLevel)) {
        oldest = at;
        oldestLevel = level;
        slot = s;
      }
    }
    if (slot < 0) {
      ++plan.unplaceable;
      ++plan.pending;
      continue;
    }
    if (const int evicted = slotPage_[std::size_t(slot)]; evicted >= 0) {
      pageSlot_[std::size_t(evicted)] = -1;
      ++plan.evictions;
    }
    slotPage_[std::size_t(slot)] = page;
    pageSlot_[std::size_t(page)] = slot;
    plan.uploads.push_back({page, slot});
    --budget;
  }
  return plan;
}

std::vector<std::uint32_t> ImageryResidency::pageTable() const {
  std::vector<std::uint32_t> table(std::size_t(layout_.pageCount()), 0u);
  for (int layer = 0; layer < layout_.layerCount(); ++layer) {
    // Coarsest level first: a page without its own slot takes its parent's entry.
    for (int m = layout_.levels(layer) - 1; m >= 0; --m) {
      const ImageryLevelPages& l = layout_.level(layer, m);
      for (int y = 0; y < l.tilesY; ++y) {
        for (int x = 0; x < l.tilesX; ++x) {
          const int page = l.firstPage + y * l.tilesX + x;
          const int slot = pageSlot_[std::size_t(page)];
          if (slot >= 0) {
            table[std::size_t(page)] = imageryPageEntry(slot, m);
          } else if (m + 1 < layout_.levels(layer)) {
            table[std::size_t(page)] =
                table[std::size_t(layout_.pageIndex({layer, m + 1, x / 2, y / 2}))];
          }
        }
      }
    }
  }
  return table;
}

bool ImageryResidency::anyPending() const {
  return std::any_of(latestWanted_.begin(), latestWanted_.end(),
                     [&](int page) { return pageSlot_[std::size_t(page)] < 0; });
}

}  // namespace tellus
