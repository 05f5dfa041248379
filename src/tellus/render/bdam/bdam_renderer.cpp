#include "tellus/render/bdam/bdam_renderer.hpp"

#include <algorithm>
#include <chrono>
#include <limits>
#include <unordered_set>

#include <spdlog/spdlog.h>

#include <fmt/format.h>

#include "tellus/core/stopwatch.hpp"

namespace tellus {
namespace {

// Exact pieces' cache keys: the node and its cut cells.
std::uint64_t exactKey(bdam::NodeId node, bdam::CutCells cut) { return node * 3 + std::uint64_t(cut); }

}  // namespace

Result<std::unique_ptr<BdamRenderer>> BdamRenderer::create(const HeightGrid& grid, const BdamOptions& options) {
  if (!(options.selection.targetPx > 0.0f)) return makeError("BDAM error target must be > 0 px");
  if (options.cacheSlots < 16) return makeError("BDAM cache of {} patches: needs at least 16", options.cacheSlots);
  if (options.patchFile.empty()) return makeError("BDAM needs a patch file (tellus build --bdam)");
  Result<bdam::PatchFile> file = bdam::PatchFile::open(options.patchFile);
  if (!file) return file.error();
  if (file->gridWidth() != grid.width || file->gridHeight() != grid.height) {
    return makeError("BDAM patch file {} was built from a {} x {} grid, the input is {} x {} (rebuild it with "
                     "'tellus build ... --bdam')",
                     options.patchFile.string(), file->gridWidth(), file->gridHeight(), grid.width, grid.height);
  }
  Result<bdam::PatchTree> tree = bdam::PatchTree::create(file->entries(), file->domainLog2(), file->leafLevel(),
                                                         file->spacingXM(), file->spacingYM());
  if (!tree) return makeError("BDAM patch file {}: {}", options.patchFile.string(), tree.error().message);
  std::unique_ptr<BdamRenderer> r(new BdamRenderer());
  r->options_ = options;
  r->grid_ = &grid;
  r->file_ = std::move(file.value());
  r->tree_ = std::move(tree.value());
  std::uint32_t slotVertices = 0, slotIndices = 0;
  for (const bdam::PatchEntry& e : r->file_.entries()) {
    slotVertices = std::max(slotVertices, e.vertices);
    slotIndices = std::max(slotIndices, e.indices);
  }
  Result<GridMeshShading> shading = GridMeshShading::create(grid, "bdam/bdam.vert", "BDAM");
  if (!shading) return shading.error();
  r->shading_ = std::move(shading.value());
  r->frame_ = 2;  // "used by the last two frames" stays well defined from the start
  r->patches_ = BdamSlotCache(std::size_t(options.cacheSlots), slotVertices, slotIndices, "patch cache");
  // Every exact piece's triangle has the same box: at most its samples and two triangles a cell.
  const bdam::Triangle piece = bdam::nodeTriangle(bdam::NodeId(2) << (r->file_.leafLevel() + bdam::kExactPieceLevels),
                                                  r->file_.domainLog2());
  const glm::ivec2 box = piece.boxMax() - piece.boxMin();
  const std::uint64_t leafSamples = std::uint64_t(box.x + 1) * std::uint64_t(box.y + 1);
  r->exactFits_ = leafSamples <= 65536;
  r->exactSlotVertices_ = std::uint32_t(std::min<std::uint64_t>(leafSamples, 65536));
  r->exactSlotIndices_ = std::uint32_t(std::uint64_t(box.x) * std::uint64_t(box.y) * 6);
  if (options.selection.exactLeaves && !r->exactFits_) {
    spdlog::warn("BDAM: exact pieces of {} x {} samples are too large (16-bit indices); the finest patches "
                 "are the stored leaves",
                 box.x + 1, box.y + 1);
  }
  spdlog::info("BDAM: {} patches (leaf level {}), {:.1f} MB file, cache of {} slots ({} vertices, {} indices each)",
               r->file_.entries().size(), r->file_.leafLevel(), double(r->file_.fileBytes()) / 1e6,
               options.cacheSlots, slotVertices, slotIndices);
  return r;
}

bool BdamRenderer::makeResident(std::uint32_t entry) {
  if (patches_.touch(entry, frame_)) return true;
  if (Status read = file_.read(entry, readVertices_, readIndices_); !read) {
    if (!dataError_) {
      spdlog::error("{}", read.error().message);
      dataError_ = read.error();
    }
    return false;
  }
  const bdam::PatchEntry& e = file_.entries()[entry];
  const glm::uvec4 record{e.origin.x, e.origin.y, std::uint32_t(bdam::nodeLevel(e.node)), 0u};
  info_.uploadBytes += patches_.put(entry, readVertices_, readIndices_, record, frame_);
  ++info_.loaded;
  return true;
}

void BdamRenderer::prepareExactPieces(const std::vector<bdam::ExactPiece>& pieces) {
  if (pieces.empty()) return;
  if (!exact_.created()) exact_ = BdamSlotCache(64, exactSlotVertices_, exactSlotIndices_, "exact-piece cache");
  std::unordered_set<bdam::NodeId> drawnExact;
  for (const bdam::ExactPiece& p : pieces) drawnExact.insert(p.node);
  for (const bdam::ExactPiece& p : pieces) {
    const bdam::Triangle t = bdam::nodeTriangle(p.node, file_.domainLog2());
    if (!bdam::touchesGrid(t, grid_->width, grid_->height)) continue;
    // The cells along a north-west edge shared with another exact piece: the lower node draws
    // them whole, the reference's way; beside a stored patch (or a piece out of view) each
    // draws its half.
    bdam::CutCells cut = bdam::CutCells::Half;
    glm::ivec2 a, b;
    if (bdam::northwestEdge(t, a, b)) {
      const bdam::NodeId across = bdam::nodeAcross(t, a, b, bdam::nodeLevel(p.node), file_.domainLog2());
      if (drawnExact.contains(across)) cut = p.node < across ? bdam::CutCells::Whole : bdam::CutCells::None;
    }
    const std::uint64_t key = exactKey(p.node, cut);
    if (!exact_.touch(key, frame_)) {
      const bdam::ExactLeafMesh mesh = bdam::exactLeafMesh(*grid_, p.node, file_.domainLog2(), cut);
      if (mesh.indices.empty()) continue;
      const glm::uvec4 record{mesh.origin.x, mesh.origin.y, std::uint32_t(file_.leafLevel() + 1), 0u};
      info_.uploadBytes += exact_.put(key, mesh.vertices, mesh.indices, record, frame_);
      ++info_.loaded;
    }
    pending_.exact.push_back({p.leafEntry, p.node, cut});
    pending_.exactKeys.push_back(key);
  }
}

void BdamRenderer::prepare(const ViewSetup& view, const RenderSettings& settings) {
  ++frame_;
  bdam::SelectionSettings selecting = options_.selection;
  selecting.exactLeaves = selecting.exactLeaves && exactFits_;
  tree_.select(LodView::fromSetup(view, settings.verticalExaggeration), selecting, selection_);
  const Stopwatch start;
  info_.loaded = 0;
  info_.uploadBytes = 0;
  pending_ = Drawn{};
  for (std::uint32_t entry : selection_.patches) {
    if (!makeResident(entry)) continue;
    pending_.patches.push_back(entry);
    pending_.patchKeys.push_back(entry);
  }
  prepareExactPieces(selection_.exactPieces);
  info_.loadMs = start.elapsedMs();
  prepared_ = true;
}

FrameStats BdamRenderer::draw(const ViewSetup& view, const RenderSettings& settings) {
  if (!prepared_) prepare(view, settings);  // a caller that does not prepare (stills)
  prepared_ = false;
  current_ = 1 - current_;
  std::swap(drawn_[std::size_t(current_)], pending_);
  const Drawn& drawn = drawn_[std::size_t(current_)];
  drawPatches(drawn, view, settings);
  ++framesDrawn_;
  FrameStats stats;
  for (std::uint32_t e : drawn.patches) {
    stats.triangles += file_.entries()[e].indices / 3;
    stats.vertices += file_.entries()[e].vertices;
  }
  if (exact_.created()) stats.triangles += exact_.triangles(drawn.exactKeys);
  const std::size_t resident = patches_.resident() + exact_.resident();
  const std::size_t patches = drawn.patches.size() + drawn.exact.size();
  stats.drawCalls = (drawn.patches.empty() ? 0 : 1) + (drawn.exact.empty() ? 0 : 1);
  stats.tilesWanted = patches;
  stats.tilesLoaded = info_.loaded;
  stats.cacheMisses = info_.loaded;
  stats.tilesResident = resident;
  stats.uploadBytes = info_.uploadBytes;
  info_.patches = patches;
  info_.exactPieces = drawn.exact.size();
  // A leaf's pieces are listed one after another (PatchTree::select).
  info_.exactLeaves = 0;
  for (std::size_t i = 0; i < drawn.exact.size(); ++i) {
    info_.exactLeaves += i == 0 || drawn.exact[i].entry != drawn.exact[i - 1].entry ? 1 : 0;
  }
  info_.resident = resident;
  info_.slots = patches_.slots() + exact_.slots();
  return stats;
}

bool BdamRenderer::drawPreviousSelection(const ViewSetup& view, const RenderSettings& settings) {
  if (framesDrawn_ < 2) return false;
  drawPatches(drawn_[std::size_t(1 - current_)], view, settings);
  return true;
}

void BdamRenderer::drawPatches(const Drawn& drawn, const ViewSetup& view, const RenderSettings& settings) {
  shading_.draw(view, settings, [&](const gl::Program& program) {
    patches_.draw(program, drawn.patchKeys);
    if (exact_.created()) exact_.draw(program, drawn.exactKeys);
  });
}

std::vector<std::string> BdamRenderer::frameReport() const {
  return {fmt::format("patches drawn {} ({} pieces of {} leaves exact), read or made this frame {} ({:.2f} ms)",
                      info_.patches, info_.exactPieces, info_.exactLeaves, info_.loaded, info_.loadMs),
          fmt::format("cache {} of {} slots", info_.resident, info_.slots)};
}

}  // namespace tellus
