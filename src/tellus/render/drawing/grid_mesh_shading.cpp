#include "tellus/render/drawing/grid_mesh_shading.hpp"

#include "tellus/render/drawing/wireframe_overlay.hpp"

namespace tellus {

Result<GridMeshShading> GridMeshShading::create(const HeightGrid& grid, const char* vertexShader, std::string_view who) {
  Result<FillAndWirePrograms> programs = loadFillAndWirePrograms(vertexShader, "common/height_texture_surface.frag");
  if (!programs) return programs.error();
  GridMeshShading s;
  s.fill_ = std::move(programs->fill);
  s.wire_ = std::move(programs->wire);
  s.heights_ = ShadingHeightTexture::create(grid, who);
  s.spacingXM_ = grid.spacingXM;
  s.spacingYM_ = grid.spacingYM;
  return s;
}

void GridMeshShading::draw(const ViewSetup& view, const RenderSettings& settings,
                           const std::function<void(const gl::Program&)>& drawWith) const {
  const glm::dvec3& eye = view.camera.position;
  const float exaggeration = settings.verticalExaggeration;
  const int stride = heights_.stride;
  for (const gl::Program* program : programs()) {
    program->set("uClipFromRelative", glm::mat4(view.relativeViewProjection()));
    program->set("uCameraGrid", glm::vec3(float(eye.x / spacingXM_), float(eye.y / spacingYM_),
                                          float(eye.z / double(exaggeration))));
    program->set("uGridScale", glm::vec3(float(spacingXM_), float(spacingYM_), exaggeration));
    program->set("uMapStride", float(stride));
    // Metres between texture samples (the fill's normals; the wire's line fading).
    program->set("uSpacing", glm::vec2(float(spacingXM_ * stride), float(spacingYM_ * stride)));
  }
  fill_.set("uExaggeration", exaggeration);
  fill_.set("uMapErrorM", heights_.errorM);
  applyShadingMode(fill_, view, settings);
  heights_.texture.bindUnit(0);
  drawWithWireframeOverlay(settings.wireframe, wire_, view, [&] { drawWith(fill_); }, [&] { drawWith(wire_); });
}

}  // namespace tellus
