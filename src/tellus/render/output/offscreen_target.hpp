#pragma once
// An offscreen render target: multisampled colour (RGBA8) + float depth, resolved into a
// single-sample texture for read-back. Sets up reversed-Z (clip control 0..1, depth cleared to
// 0, GL_GREATER). Needs a current GL 4.5 context.
#include <glm/vec3.hpp>

#include "tellus/core/depth_image.hpp"
#include "tellus/core/result.hpp"
#include "tellus/core/rgb_image.hpp"
#include "tellus/gl/framebuffer.hpp"
#include "tellus/gl/texture.hpp"

namespace tellus {

class OffscreenTarget {
 public:
  // width x height pixels, `samples` MSAA samples (1 = no MSAA).
  static Result<OffscreenTarget> create(int width, int height, int samples);

  // Binds the target, sets the viewport and reversed-Z depth state, clears to `clearSrgb`.
  void begin(const glm::u8vec3& clearSrgb);
  // Resolves the samples and reads the image back (top row first).
  RgbImage readRgb();

  // The same in steps, for a window that draws an overlay (its UI) over the terrain:
  // resolve() the samples into the single-sample image; bindResolved() to draw over it (no
  // depth test: the overlay's own state); readResolvedRgb() to read it back; presentTo() to
  // copy it into another framebuffer (0: the window's) of size width x height, scaled.
  void resolve();
  void bindResolved();
  RgbImage readResolvedRgb();
  void presentTo(GLuint framebuffer, int width, int height);
  // Reads the depth buffer back (top row first). With MSAA, one sample per pixel is taken;
  // measurements of depth (screen-space error) use a single-sample target.
  DepthImage readDepth();

  int width() const { return width_; }
  int height() const { return height_; }

 private:
  int width_ = 0, height_ = 0, samples_ = 1;
  gl::Texture colour_, depth_, resolved_, resolvedDepth_;
  gl::Framebuffer drawFbo_, resolveFbo_;
};

}  // namespace tellus
