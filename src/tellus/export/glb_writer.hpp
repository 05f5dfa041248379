#pragma once
// One triangle mesh as a binary glTF 2.0 (.glb), through tinygltf: what `export --gltf` and
// each content tile of `export --3d-tiles` write.
//
// One scene, one node (optionally translated, with extras), one mesh of one primitive:
// POSITION (float; min and max given, as glTF requires), NORMAL (float, optional), TEXCOORD_0
// (float, optional), COLOR_0 (normalized RGBA bytes, optional), and indices, 16-bit below 65,536 vertices (65535 is the
// primitive-restart value, which glTF forbids as an index) and 32-bit from there. One
// material: grey, fully rough, not metallic. The caller gives positions in glTF's frame
// (y up, right-handed, metres).
//
// With `quantize`, the attributes are stored as KHR_mesh_quantization allows (the extension
// is then used and required): positions as unsigned 16-bit integers over the mesh's bounding
// box, which the node's translation and (uniform) scale map back to metres, normals as
// normalized signed bytes, texture coordinates as normalized unsigned 16-bit integers; about
// half the bytes. A position moves by at most sqrt(3)/2 of the box's longest side / 65535.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tellus/core/result.hpp"

namespace tellus {

struct GlbMesh {
  std::string name;                    // of the node and the mesh
  std::vector<float> positions;        // x, y, z a vertex
  std::vector<float> normals;          // x, y, z a vertex, unit length; empty: none
  std::vector<float> texcoords;        // s, t a vertex (TEXCOORD_0); empty: none
  std::vector<std::uint8_t> colours;   // r, g, b, a a vertex; empty: none
  std::vector<std::uint32_t> indices;  // three a triangle, counter-clockwise seen from outside
  std::optional<std::array<double, 3>> translation;  // the node's, metres (double: ECEF fits)
  nlohmann::json extras;               // the node's extras; null: none
  std::string generator;               // asset.generator
  bool quantize = false;               // KHR_mesh_quantization (above)
  // A JPEG image the material's base colour samples through TEXCOORD_0 (linear filtering,
  // clamped to its edges); empty: none (the grey material alone).
  std::vector<std::uint8_t> textureJpeg;
};

// The .glb bytes. Errors: arrays of mismatched sizes, indices out of range, no vertices.
Result<std::string> encodeGlb(const GlbMesh& mesh);

}  // namespace tellus
