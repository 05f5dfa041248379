#include "tellus/render/drawing/wireframe_overlay.hpp"

#include <cmath>

#include <glm/trigonometric.hpp>

namespace tellus {

Result<FillAndWirePrograms> loadFillAndWirePrograms(const char* vertexShader,
                                                    const char* fillFragmentShader) {
  Result<gl::Program> fill = gl::Program::fromFiles(
      {{GL_VERTEX_SHADER, vertexShader}, {GL_FRAGMENT_SHADER, fillFragmentShader}});
  if (!fill) return fill.error();
  Result<gl::Program> wire = gl::Program::fromFiles(
      {{GL_VERTEX_SHADER, vertexShader}, {GL_FRAGMENT_SHADER, "terrain/wire.frag"}});
  if (!wire) return wire.error();
  return FillAndWirePrograms{std::move(fill.value()), std::move(wire.value())};
}

void drawWithWireframeOverlay(bool wireframe, const gl::Program& wire, const ViewSetup& view,
                              const std::function<void()>& fill,
                              const std::function<void()>& lines) {
  if (!wireframe) {
    fill();
    return;
  }
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(-1.0f, -1.0f);  // reversed-Z: pushes the surface away from the lines
  fill();
  glDisable(GL_POLYGON_OFFSET_FILL);
  wire.set("uWireColour", glm::vec4(0.04f, 0.04f, 0.04f, 0.85f));
  wire.set("uPixelAngle",
           float(2.0 * std::tan(glm::radians(view.camera.fovYDeg) * 0.5) / view.height));
  glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
  glDepthFunc(GL_GEQUAL);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  lines();
  glDisable(GL_BLEND);
  glDepthFunc(GL_GREATER);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
}

}  // namespace tellus
