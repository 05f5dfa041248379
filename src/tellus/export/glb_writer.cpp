#include "tellus/export/glb_writer.hpp"

#include <algorithm>
#include <limits>
#include <sstream>

#include <tiny_gltf.h>

namespace tellus {
namespace {

// Appends `values` as a buffer view; `stride` (bytes, 0: tightly packed) for vertex
// attributes whose elements are not 4-byte multiples, as glTF requires of vertex strides.
template <typename T>
int appendView(tinygltf::Model& model, const std::vector<T>& values, int target, std::size_t stride = 0) {
  tinygltf::Buffer& buffer = model.buffers[0];
  while (buffer.data.size() % 4 != 0) buffer.data.push_back(0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = buffer.data.size();
  view.byteLength = values.size() * sizeof(T);
  view.byteStride = stride;
  view.target = target;
  const auto* bytes = reinterpret_cast<const unsigned char*>(values.data());
  buffer.data.insert(buffer.data.end(), bytes, bytes + view.byteLength);
  model.bufferViews.push_back(view);
  return int(model.bufferViews.size()) - 1;
}

int appendAccessor(tinygltf::Model& model, int view, int componentType, int type,
                   std::size_t count, bool normalized = false) {
  tinygltf::Accessor accessor;
  accessor.bufferView = view;
  accessor.componentType = componentType;
  accessor.type = type;
  accessor.count = count;
  accessor.normalized = normalized;
  model.accessors.push_back(accessor);
  return int(model.accessors.size()) - 1;
}

// nlohmann's JSON as tinygltf's value tree.
tinygltf::Value toGltfValue(const nlohmann::json& json) {
  switch (json.type()) {
    case nlohmann::json::value_t::boolean: return tinygltf::Value(json.get<bool>());
    case nlohmann::json::value_t::number_integer:
    case nlohmann::json::value_t::number_unsigned: return tinygltf::Value(json.get<int>());
    case nlohmann::json::value_t::number_float: return tinygltf::Value(json.get<double>());
    case nlohmann::json::value_t::string: return tinygltf::Value(json.get<std::string>());
    case nlohmann::json::value_t::array: {
      tinygltf::Value::Array array;
      for (const nlohmann::json& item : json) array.push_back(toGltfValue(item));
      return tinygltf::Value(std::move(array));
    }
    case nlohmann::json::value_t::object: {
      tinygltf::Value::Object object;
      for (const auto& [key, item] : json.items()) object[key] = toGltfValue(item);
      return tinygltf::Value(std::move(object));
    }
    default: return tinygltf::Value();
  }
}

}  // namespace

Result<std::string> encodeGlb(const GlbMesh& mesh) {
  const std::size_t count = mesh.positions.size() / 3;
  if (count == 0 || mesh.positions.size() != 3 * count ||
      (!mesh.normals.empty() && mesh.normals.size() != 3 * count) ||
      (!mesh.texcoords.empty() && mesh.texcoords.size() != 2 * count) ||
      (!mesh.colours.empty() && mesh.colours.size() != 4 * count) || mesh.indices.size() % 3 != 0) {
    return makeError("glTF mesh '{}': {} position values, {} normal values, {} colour values, {} "
                     "indices do not make whole vertices and triangles",
                     mesh.name, mesh.positions.size(), mesh.normals.size(), mesh.colours.size(),
                     mesh.indices.size());
  }
  if (std::any_of(mesh.indices.begin(), mesh.indices.end(), [&](std::uint32_t i) { return i >= count; })) {
    return makeError("glTF mesh '{}': an index beyond its {} vertices", mesh.name, count);
  }
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = mesh.generator;
  model.buffers.resize(1);
  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  std::array<double, 3> lo, hi;
  lo.fill(std::numeric_limits<double>::max());
  hi.fill(-std::numeric_limits<double>::max());
  for (std::size_t k = 0; k < count; ++k) {
    for (std::size_t c = 0; c < 3; ++c) {
      lo[c] = std::min(lo[c], double(mesh.positions[3 * k + c]));
      hi[c] = std::max(hi[c], double(mesh.positions[3 * k + c]));
    }
  }
  // KHR_mesh_quantization: positions on a grid of `step` metres from the box's corner `lo`.
  double step = 1.0;
  if (mesh.quantize) {
    step = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 1e-6}) / 65535.0;
    std::vector<std::uint16_t> positions(4 * count, 0);  // x, y, z and padding to 8 bytes
    std::array<double, 3> qmax{0.0, 0.0, 0.0};
    for (std::size_t k = 0; k < count; ++k) {
      for (std::size_t c = 0; c < 3; ++c) {
        const double q = std::clamp(std::round((double(mesh.positions[3 * k + c]) - lo[c]) / step), 0.0, 65535.0);
        positions[4 * k + c] = std::uint16_t(q);
        qmax[c] = std::max(qmax[c], q);
      }
    }
    const int accessor = appendAccessor(model, appendView(model, positions, TINYGLTF_TARGET_ARRAY_BUFFER, 8),
                                        TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC3, count);
    model.accessors[std::size_t(accessor)].minValues = {0.0, 0.0, 0.0};
    model.accessors[std::size_t(accessor)].maxValues = {qmax[0], qmax[1], qmax[2]};
    primitive.attributes["POSITION"] = accessor;
    if (!mesh.normals.empty()) {
      std::vector<std::int8_t> normals(4 * count, 0);  // x, y, z and padding to 4 bytes
      for (std::size_t k = 0; k < count; ++k) {
        for (std::size_t c = 0; c < 3; ++c) {
          normals[4 * k + c] = std::int8_t(std::lround(std::clamp(mesh.normals[3 * k + c], -1.0f, 1.0f) * 127.0f));
        }
      }
      primitive.attributes["NORMAL"] =
          appendAccessor(model, appendView(model, normals, TINYGLTF_TARGET_ARRAY_BUFFER, 4),
                         TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_TYPE_VEC3, count, true);
    }
    if (!mesh.texcoords.empty()) {
      std::vector<std::uint16_t> texcoords(2 * count);
      for (std::size_t k = 0; k < 2 * count; ++k) {
        texcoords[k] = std::uint16_t(std::lround(std::clamp(mesh.texcoords[k], 0.0f, 1.0f) * 65535.0f));
      }
      primitive.attributes["TEXCOORD_0"] =
          appendAccessor(model, appendView(model, texcoords, TINYGLTF_TARGET_ARRAY_BUFFER),
                         TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC2, count, true);
    }
    model.extensionsUsed.push_back("KHR_mesh_quantization");
    model.extensionsRequired.push_back("KHR_mesh_quantization");
  } else {
    const int accessor = appendAccessor(model, appendView(model, mesh.positions, TINYGLTF_TARGET_ARRAY_BUFFER),
                                        TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, count);
    model.accessors[std::size_t(accessor)].minValues = {lo[0], lo[1], lo[2]};
    model.accessors[std::size_t(accessor)].maxValues = {hi[0], hi[1], hi[2]};
    primitive.attributes["POSITION"] = accessor;
    if (!mesh.normals.empty()) {
      primitive.attributes["NORMAL"] =
          appendAccessor(model, appendView(model, mesh.normals, TINYGLTF_TARGET_ARRAY_BUFFER),
                         TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, count);
    }
    if (!mesh.texcoords.empty()) {
      primitive.attributes["TEXCOORD_0"] =
          appendAccessor(model, appendView(model, mesh.texcoords, TINYGLTF_TARGET_ARRAY_BUFFER),
                         TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, count);
    }
  }
  if (!mesh.colours.empty()) {
    primitive.attributes["COLOR_0"] =
        appendAccessor(model, appendView(model, mesh.colours, TINYGLTF_TARGET_ARRAY_BUFFER),
                       TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_VEC4, count, true);
  }
  if (count < 65536) {
    const std::vector<std::uint16_t> small(mesh.indices.begin(), mesh.indices.end());
    primitive.indices =
        appendAccessor(model, appendView(model, small, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
                       TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_SCALAR, small.size());
  } else {
    primitive.indices =
        appendAccessor(model, appendView(model, mesh.indices, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
                       TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, mesh.indices.size());
  }
  tinygltf::Material material;
  material.name = "terrain";
  material.pbrMetallicRoughness.baseColorFactor = {0.8, 0.8, 0.8, 1.0};
  material.pbrMetallicRoughness.metallicFactor = 0.0;
  material.pbrMetallicRoughness.roughnessFactor = 1.0;
  if (!mesh.textureJpeg.empty()) {
    if (mesh.texcoords.empty()) {
      return makeError("glTF mesh '{}': a texture without texture coordinates", mesh.name);
    }
    tinygltf::Image image;
    image.name = mesh.name;
    image.mimeType = "image/jpeg";
    image.bufferView = appendView(model, mesh.textureJpeg, 0);
    model.images.push_back(image);
    tinygltf::Sampler sampler;
    sampler.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
    sampler.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
    sampler.wrapS = TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
    sampler.wrapT = TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
    model.samplers.push_back(sampler);
    tinygltf::Texture texture;
    texture.sampler = 0;
    texture.source = 0;
    model.textures.push_back(texture);
    material.pbrMetallicRoughness.baseColorTexture.index = 0;
    material.pbrMetallicRoughness.baseColorFactor = {1.0, 1.0, 1.0, 1.0};
  }
  model.materials.push_back(material);
  primitive.material = 0;
  tinygltf::Mesh gltfMesh;
  gltfMesh.name = mesh.name;
  gltfMesh.primitives.push_back(primitive);
  model.meshes.push_back(gltfMesh);

  tinygltf::Node node;
  node.name = mesh.name;
  node.mesh = 0;
  std::array<double, 3> translation{0.0, 0.0, 0.0};
  if (mesh.translation) translation = *mesh.translation;
  if (mesh.quantize) {
    // The node takes the grid back to metres: p = translation + lo + step * q.
    for (std::size_t c = 0; c < 3; ++c) translation[c] += lo[c];
    node.scale = {step, step, step};
  }
  if (mesh.translation || mesh.quantize) node.translation.assign(translation.begin(), translation.end());
  if (!mesh.extras.is_null()) node.extras = toGltfValue(mesh.extras);
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes = {0};
  model.scenes.push_back(scene);
  model.defaultScene = 0;

  tinygltf::TinyGLTF writer;
  std::ostringstream glb;
  if (!writer.WriteGltfSceneToStream(&model, glb, false, true)) {
    return makeError("tinygltf could not write the glTF mesh '{}'", mesh.name);
  }
  return glb.str();
}

}  // namespace tellus
