#include "tellus/render/globe/globe_shading.hpp"

#include <glm/matrix.hpp>

#include "tellus/core/enu_frame.hpp"
#include "tellus/core/geodesy.hpp"

namespace tellus {

glm::vec3 globeSunEcef(const ViewSetup& view, const RenderSettings& settings) {
  const wgs84::Geodetic under = wgs84::ecefToGeodetic(view.camera.position);
  const EnuFrame local({under.latRad, under.lonRad, 0.0});
  return glm::vec3(local.directionToEcef(glm::dvec3(settings.shading.sunDirection())));
}

void setGlobeFillUniforms(const gl::Program& fill, const ViewSetup& view,
                          const RenderSettings& settings, const glm::vec3& sunEcef) {
  fill.set("uSunEcef", sunEcef);
  fill.set("uAtmosphere", settings.sky);
  fill.set("uEyeEcef", glm::vec3(view.camera.position));
  applyShadingMode(fill, view, settings);
}

Result<GlobeSky> GlobeSky::create() {
  Result<gl::Program> program = gl::Program::fromFiles(
      {{GL_VERTEX_SHADER, "globe/sky.vert"}, {GL_FRAGMENT_SHADER, "globe/sky.frag"}});
  if (!program) return program.error();
  GlobeSky sky;
  sky.program_ = std::move(program.value());
  sky.vertices_ = gl::VertexArray::create();
  return sky;
}

void GlobeSky::draw(const ViewSetup& view, const glm::vec3& sunEcef) const {
  program_.use();
  program_.set("uInverseViewProjection", glm::mat4(glm::inverse(view.relativeViewProjection())));
  program_.set("uEye", glm::vec3(view.camera.position));
  program_.set("uSunEcef", sunEcef);
  wgs84::Geodetic under = wgs84::ecefToGeodetic(view.camera.position);
  under.heightM = 0.0;
  program_.set("uGroundRadius", float(glm::length(wgs84::geodeticToEcef(under))));
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  vertices_.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDepthMask(GL_TRUE);
  glEnable(GL_DEPTH_TEST);
}

}  // namespace tellus
