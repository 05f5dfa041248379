#pragma once
// BDAM (seed 004 section 2.2; Cignoni et al. 2003): the patch bintree of a patch file (made by
// `tellus build --bdam`) traversed for the view in prepare() (lod/bdam/bdam_selection.hpp), the
// patches it selects read on demand from the file into a GPU cache of fixed-size slots
// (bdam_slot_cache.hpp), and drawn with one glMultiDrawElementsBaseVertex a frame. Leaves whose
// diamond still asks for more detail are drawn exact, made from the grid at the grid's full
// resolution (lod/bdam/bdam_exact_leaf.hpp) into a second cache of larger slots, and drawn with
// a second multi-draw. Patches never change on the GPU: the CPU only chooses which to draw.
// Needs a current GL 4.5 context for its whole life.
#include <array>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tellus/formats/bdam/bdam_file.hpp"
#include "tellus/core/result.hpp"
#include "tellus/dem/height_grid.hpp"
#include "tellus/gl/buffer.hpp"
#include "tellus/gl/program.hpp"
#include "tellus/gl/texture.hpp"
#include "tellus/gl/vertex_array.hpp"
#include "tellus/lod/bdam/bdam_exact_leaf.hpp"
#include "tellus/lod/bdam/bdam_selection.hpp"
#include "tellus/render/bdam/bdam_slot_cache.hpp"
#include "tellus/render/drawing/grid_mesh_shading.hpp"
#include "tellus/render/terrain_renderer.hpp"

namespace tellus {

struct BdamOptions {
  std::string name = "bdam";
  std::filesystem::path patchFile;   // empty: the caller's default (NAME.bdam beside the input)
  bdam::SelectionSettings selection;
  int cacheSlots = 4096;             // patches the GPU cache holds at first (it grows if a frame needs more)
};

// What the last prepare() and draw() did.
struct BdamFrameInfo {
  std::size_t patches = 0;        // drawn (stored patches and exact leaves)
  std::size_t exactPieces = 0;    // of them, pieces of leaves drawn exact
  std::size_t exactLeaves = 0;    // the leaves they belong to
  std::size_t loaded = 0;         // read from the file for this frame
  std::size_t resident = 0;       // in the GPU cache after the frame
  std::size_t slots = 0;          // the cache's size
  double loadMs = 0.0;            // reading and uploading them
  std::uint64_t uploadBytes = 0;  // what they sent to the GPU
};

class BdamRenderer final : public TerrainRenderer {
 public:
  // `grid` (for shading) must be the grid the patch file was built from and outlive the
  // renderer. Errors: a missing or corrupt patch file, one built from another grid, shaders.
  static Result<std::unique_ptr<BdamRenderer>> create(const HeightGrid& grid, const BdamOptions& options);

  std::string_view name() const override { return options_.name; }
  void prepare(const ViewSetup& view, const RenderSettings& settings) override;
  FrameStats draw(const ViewSetup& view, const RenderSettings& settings) override;
  bool drawPreviousSelection(const ViewSetup& view, const RenderSettings& settings) override;
  std::vector<std::string> frameReport() const override;
  // The first patch that failed its read or its checks (bdam_file.hpp).
  std::optional<Error> dataError() const override { return dataError_; }

  const bdam::PatchFile& file() const { return file_; }
  const bdam::PatchTree& tree() const { return tree_; }
  // A piece of a leaf drawn exact: the leaf's table entry, the piece's node and what it drew of
  // the cells its north-west edge cuts.
  struct DrawnExactPiece {
    std::uint32_t entry = 0;
    bdam::NodeId node = 0;
    bdam::CutCells cut = bdam::CutCells::Half;
  };
  // The stored patches (table entries) and the exact leaves the last draw() drew.
  const std::vector<std::uint32_t>& lastPatches() const { return drawn_[std::size_t(current_)].patches; }
  const std::vector<DrawnExactPiece>& lastExactPieces() const { return drawn_[std::size_t(current_)].exact; }
  const HeightGrid& grid() const { return *grid_; }
  const BdamFrameInfo& lastFrame() const { return info_; }
  void setTargetPx(float targetPx) { options_.selection.targetPx = targetPx; }

 private:
  // One frame's cut as drawn.
  struct Drawn {
    std::vector<std::uint32_t> patches;  // table entries
    std::vector<DrawnExactPiece> exact;
    std::vector<std::uint64_t> patchKeys, exactKeys;  // their cache keys
  };
  BdamRenderer() = default;
  // Makes `entry` resident; false when the file read failed (logged once and kept as
  // dataError(); the patch is skipped).
  bool makeResident(std::uint32_t entry);
  // Chooses each exact piece's cut cells (bdam_exact_leaf.hpp) and makes it resident.
  void prepareExactPieces(const std::vector<bdam::ExactPiece>& pieces);
  void drawPatches(const Drawn& drawn, const ViewSetup& view, const RenderSettings& settings);

  BdamOptions options_;
  const HeightGrid* grid_ = nullptr;
  bdam::PatchFile file_;
  bdam::PatchTree tree_;
  bdam::Selection selection_;
  Drawn pending_;
  bool prepared_ = false;
  std::array<Drawn, 2> drawn_;
  int current_ = 0;
  int framesDrawn_ = 0;
  std::uint64_t frame_ = 0;
  BdamSlotCache patches_;        // stored patches, keyed by table entry
  BdamSlotCache exact_;          // exact pieces, keyed by node * 3 + cut; made at the first
  bool exactFits_ = false;       // pieces small enough for 16-bit indices
  std::uint32_t exactSlotVertices_ = 0, exactSlotIndices_ = 0;
  std::vector<bdam::PackedVertex> readVertices_;
  std::vector<std::uint16_t> readIndices_;
  BdamFrameInfo info_;
  GridMeshShading shading_;
  std::optional<Error> dataError_;
};

}  // namespace tellus
