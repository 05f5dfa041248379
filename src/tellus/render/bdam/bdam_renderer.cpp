#include "tellus/render/bdam/bdam_renderer.hpp"

#include <algorithm>
#include <chrono>
#include <limits>

#include <spdlog/spdlog.h>

#include <fmt/format.h>

#include "tellus/core/stopwatch.hpp"

namespace tellus {

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
  r->file_ = std::move(file.value());
  r->tree_ = std::move(tree.value());
  for (const bdam::PatchEntry& e : r->file_.entries()) {
    r->slotVertices_ = std::max(r->slotVertices_, e.vertices);
    r->slotIndices_ = std::max(r->slotIndices_, e.indices);
  }
  Result<GridMeshShading> shading = GridMeshShading::create(grid, "bdam/bdam.vert", "BDAM");
  if (!shading) return shading.error();
  r->shading_ = std::move(shading.value());
  for (const gl::Program* program : r->shading_.programs()) program->set("uSlotVertices", int(r->slotVertices_));
  r->slotOfEntry_.assign(r->file_.entries().size(), -1);
  r->array_ = gl::VertexArray::create();
  r->frame_ = 2;  // "used by the last two frames" stays well defined from the start
  const std::size_t slots = std::size_t(options.cacheSlots);
  r->vertices_ = gl::Buffer(slots * r->slotVertices_ * sizeof(bdam::PackedVertex), nullptr, GL_DYNAMIC_STORAGE_BIT);
  r->indices_ = gl::Buffer(slots * r->slotIndices_ * sizeof(std::uint16_t), nullptr, GL_DYNAMIC_STORAGE_BIT);
  r->slotRecords_ = gl::Buffer(slots * sizeof(glm::uvec4), nullptr, GL_DYNAMIC_STORAGE_BIT);
  r->entryOfSlot_.assign(slots, -1);
  r->slotLastUsed_.assign(slots, 0);
  const GLuint vao = r->array_.id();
  glVertexArrayVertexBuffer(vao, 0, r->vertices_.id(), 0, GLsizei(sizeof(bdam::PackedVertex)));
  glEnableVertexArrayAttrib(vao, 0);
  glVertexArrayAttribIFormat(vao, 0, 2, GL_UNSIGNED_SHORT, 0);
  glVertexArrayAttribBinding(vao, 0, 0);
  glEnableVertexArrayAttrib(vao, 1);
  glVertexArrayAttribFormat(vao, 1, 1, GL_FLOAT, GL_FALSE, 4);
  glVertexArrayAttribBinding(vao, 1, 0);
  r->array_.setIndexBuffer(r->indices_);
  spdlog::info("BDAM: {} patches (leaf level {}), {:.1f} MB file, cache of {} slots ({} vertices, {} indices each)",
               r->file_.entries().size(), r->file_.leafLevel(), double(r->file_.fileBytes()) / 1e6, slots,
               r->slotVertices_, r->slotIndices_);
  return r;
}

int BdamRenderer::freeSlot() {
  int best = -1;
  std::uint64_t oldest = std::numeric_limits<std::uint64_t>::max();
  for (std::size_t s = 0; s < entryOfSlot_.size(); ++s) {
    if (entryOfSlot_[s] < 0) return int(s);
    // Never a patch this frame or the previous one drew (popping redraws the previous frame).
    if (slotLastUsed_[s] + 1 < frame_ && slotLastUsed_[s] < oldest) {
      oldest = slotLastUsed_[s];
      best = int(s);
    }
  }
  if (best >= 0) slotOfEntry_[std::size_t(entryOfSlot_[std::size_t(best)])] = -1;
  return best;
}

void BdamRenderer::grow() {
  const std::size_t old = entryOfSlot_.size(), slots = old * 2;
  const auto regrow = [&](gl::Buffer& buffer, std::size_t bytesPerSlot) {
    gl::Buffer bigger(slots * bytesPerSlot, nullptr, GL_DYNAMIC_STORAGE_BIT);
    glCopyNamedBufferSubData(buffer.id(), bigger.id(), 0, 0, GLsizeiptr(old * bytesPerSlot));
    buffer = std::move(bigger);
  };
  regrow(vertices_, slotVertices_ * sizeof(bdam::PackedVertex));
  regrow(indices_, slotIndices_ * sizeof(std::uint16_t));
  regrow(slotRecords_, sizeof(glm::uvec4));
  glVertexArrayVertexBuffer(array_.id(), 0, vertices_.id(), 0, GLsizei(sizeof(bdam::PackedVertex)));
  array_.setIndexBuffer(indices_);
  entryOfSlot_.resize(slots, -1);
  slotLastUsed_.resize(slots, 0);
  spdlog::info("BDAM: the patch cache grows to {} slots (a frame needs more than {})", slots, old);
}

bool BdamRenderer::makeResident(std::uint32_t entry) {
  if (int slot = slotOfEntry_[entry]; slot >= 0) {
    slotLastUsed_[std::size_t(slot)] = frame_;
    return true;
  }
  if (Status read = file_.read(entry, readVertices_, readIndices_); !read) {
    if (!dataError_) {
      spdlog::error("{}", read.error().message);
      dataError_ = read.error();
    }
    return false;
  }
  int slot = freeSlot();
  if (slot < 0) {
    grow();
    slot = freeSlot();
  }
  const bdam::PatchEntry& e = file_.entries()[entry];
  const std::size_t s = std::size_t(slot);
  vertices_.upload(s * slotVertices_ * sizeof(bdam::PackedVertex), readVertices_.size() * sizeof(bdam::PackedVertex),
                   readVertices_.data());
  indices_.upload(s * slotIndices_ * sizeof(std::uint16_t), readIndices_.size() * sizeof(std::uint16_t),
                  readIndices_.data());
  const glm::uvec4 record{e.origin.x, e.origin.y, std::uint32_t(bdam::nodeLevel(e.node)), 0u};
  slotRecords_.upload(s * sizeof(glm::uvec4), sizeof(record), &record);
  if (entryOfSlot_[s] < 0) ++residentCount_;  // else it replaces an evicted patch
  slotOfEntry_[entry] = slot;
  entryOfSlot_[s] = entry;
  slotLastUsed_[s] = frame_;
  ++info_.loaded;
  info_.uploadBytes += readVertices_.size() * sizeof(bdam::PackedVertex) +
                       readIndices_.size() * sizeof(std::uint16_t) + sizeof(record);
  return true;
}

void BdamRenderer::prepare(const ViewSetup& view, const RenderSettings& settings) {
  ++frame_;
  tree_.select(LodView::fromSetup(view, settings.verticalExaggeration), options_.selection, pending_);
  const Stopwatch start;
  info_.loaded = 0;
  info_.uploadBytes = 0;
  std::erase_if(pending_, [&](std::uint32_t entry) { return !makeResident(entry); });
  info_.loadMs = start.elapsedMs();
  prepared_ = true;
}

FrameStats BdamRenderer::draw(const ViewSetup& view, const RenderSettings& settings) {
  if (!prepared_) prepare(view, settings);  // a caller that does not prepare (stills)
  prepared_ = false;
  current_ = 1 - current_;
  std::swap(drawn_[std::size_t(current_)], pending_);
  const std::vector<std::uint32_t>& entries = drawn_[std::size_t(current_)];
  drawPatches(entries, view, settings);
  ++framesDrawn_;
  FrameStats stats;
  for (std::uint32_t e : entries) {
    stats.triangles += file_.entries()[e].indices / 3;
    stats.vertices += file_.entries()[e].vertices;
  }
  const std::size_t resident = residentCount_;
  stats.drawCalls = entries.empty() ? 0 : 1;
  stats.tilesWanted = entries.size();
  stats.tilesLoaded = info_.loaded;
  stats.cacheMisses = info_.loaded;
  stats.tilesResident = resident;
  stats.uploadBytes = info_.uploadBytes;
  info_.patches = entries.size();
  info_.resident = resident;
  info_.slots = entryOfSlot_.size();
  return stats;
}

bool BdamRenderer::drawPreviousSelection(const ViewSetup& view, const RenderSettings& settings) {
  if (framesDrawn_ < 2) return false;
  drawPatches(drawn_[std::size_t(1 - current_)], view, settings);
  return true;
}

void BdamRenderer::drawPatches(const std::vector<std::uint32_t>& entries, const ViewSetup& view,
                               const RenderSettings& settings) {
  std::vector<GLsizei> counts;
  std::vector<const void*> offsets;
  std::vector<GLint> baseVertices;
  for (std::uint32_t e : entries) {
    const int slot = slotOfEntry_[e];
    if (slot < 0) continue;  // evicted since (cannot happen for the last two frames)
    counts.push_back(GLsizei(file_.entries()[e].indices));
    offsets.push_back(reinterpret_cast<const void*>(std::size_t(slot) * slotIndices_ * sizeof(std::uint16_t)));
    baseVertices.push_back(GLint(std::size_t(slot) * slotVertices_));
  }
  slotRecords_.bindBase(GL_SHADER_STORAGE_BUFFER, 0);
  shading_.draw(view, settings, [&](const gl::Program& program) {
    if (counts.empty()) return;
    program.use();
    array_.bind();
    glMultiDrawElementsBaseVertex(GL_TRIANGLES, counts.data(), GL_UNSIGNED_SHORT, offsets.data(),
                                  GLsizei(counts.size()), baseVertices.data());
  });
}

std::vector<std::string> BdamRenderer::frameReport() const {
  return {fmt::format("patches drawn {}, read this frame {} ({:.2f} ms)", info_.patches,
                      info_.loaded, info_.loadMs),
          fmt::format("cache {} of {} slots", info_.resident, info_.slots)};
}

}  // namespace tellus
