#include "tellus/render/stacks/stack_sky_texture.hpp"

#include "tellus/lod/stacks/stack_sky_heights.hpp"

namespace tellus {

void StackSkyTexture::update(const StackTerrain& finest) {
  const StackSkyHeights sky = stackSkyHeights(finest);
  if (texture_.id() == 0 || texture_.width() != sky.width || texture_.height() != sky.height) {
    texture_ = gl::Texture::create2D(GL_R16, sky.width, sky.height);
    texture_.setFilter(GL_LINEAR, GL_LINEAR);
    texture_.setWrap(GL_CLAMP_TO_EDGE);
  }
  glPixelStorei(GL_UNPACK_ALIGNMENT, 2);
  texture_.upload2D(0, 0, 0, sky.width, sky.height, GL_RED, GL_UNSIGNED_SHORT, sky.values.data());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  // Value i spans finest columns i * f .. i * f + f - 1 (world x = column * spacing): its centre,
  // texel coordinate i + 1/2, lies at world (i * f + (f - 1) / 2) * spacing.
  const double f = double(sky.factor);
  worldToTexel_ = float(1.0 / (f * sky.spacingM));
  texelOffset_ = float(0.5 - (f - 1.0) / (2.0 * f));
  scaleM_ = float(sky.scaleM * 65535.0);
  spanM_ = float(f * sky.spacingM);
}

void StackSkyTexture::apply(const gl::Program& program) const {
  texture_.bindUnit(kUnit);
  program.set("uStackSkyWorldToTexel", worldToTexel_);
  program.set("uStackSkyTexelOffset", texelOffset_);
  program.set("uStackSkyScaleM", scaleM_);
  program.set("uStackSkySpanM", spanM_);
}

}  // namespace tellus
