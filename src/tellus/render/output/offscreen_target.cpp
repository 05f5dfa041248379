#include "tellus/render/output/offscreen_target.hpp"

#include <algorithm>
#include <cstring>

#include <glm/gtc/type_precision.hpp>

#include "tellus/gl/gpu_wait.hpp"

namespace tellus {

Result<OffscreenTarget> OffscreenTarget::create(int width, int height, int samples) {
  GLint maxSize = 0, maxSamples = 0;
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxSize);
  glGetIntegerv(GL_MAX_SAMPLES, &maxSamples);
  if (width < 1 || height < 1 || width > maxSize || height > maxSize) {
    return makeError("image size {}x{} is outside 1..{} pixels", width, height, maxSize);
  }
  OffscreenTarget target;
  target.width_ = width;
  target.height_ = height;
  target.samples_ = std::clamp(samples, 1, std::max(1, int(maxSamples)));
  if (target.samples_ > 1) {
    target.colour_ = gl::Texture::create2DMultisample(GL_RGBA8, width, height, target.samples_);
    target.depth_ =
        gl::Texture::create2DMultisample(GL_DEPTH_COMPONENT32F, width, height, target.samples_);
  } else {
    target.colour_ = gl::Texture::create2D(GL_RGBA8, width, height);
    target.depth_ = gl::Texture::create2D(GL_DEPTH_COMPONENT32F, width, height);
  }
  if (glGetError() == GL_OUT_OF_MEMORY) {
    return makeError("not enough GPU memory for a {}x{} image with {} samples per pixel", width,
                     height, target.samples_);
  }
  target.drawFbo_ = gl::Framebuffer::create();
  target.drawFbo_.attach(GL_COLOR_ATTACHMENT0, target.colour_);
  target.drawFbo_.attach(GL_DEPTH_ATTACHMENT, target.depth_);
  if (Status complete = target.drawFbo_.checkComplete(); !complete) return complete.error();
  target.resolved_ = gl::Texture::create2D(GL_RGBA8, width, height);
  target.resolvedDepth_ = gl::Texture::create2D(GL_DEPTH_COMPONENT32F, width, height);
  target.resolveFbo_ = gl::Framebuffer::create();
  target.resolveFbo_.attach(GL_COLOR_ATTACHMENT0, target.resolved_);
  target.resolveFbo_.attach(GL_DEPTH_ATTACHMENT, target.resolvedDepth_);
  if (Status complete = target.resolveFbo_.checkComplete(); !complete) return complete.error();
  return target;
}

void OffscreenTarget::begin(const glm::u8vec3& clearSrgb) {
  drawFbo_.bind();
  glViewport(0, 0, width_, height_);
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GREATER);
  glDepthMask(GL_TRUE);
  const float clear[4] = {clearSrgb.r / 255.0f, clearSrgb.g / 255.0f, clearSrgb.b / 255.0f, 1.0f};
  const float clearDepth = 0.0f;
  glClearNamedFramebufferfv(drawFbo_.id(), GL_COLOR, 0, clear);
  glClearNamedFramebufferfv(drawFbo_.id(), GL_DEPTH, 0, &clearDepth);
}

RgbImage OffscreenTarget::readRgb() {
  resolve();
  return readResolvedRgb();
}

void OffscreenTarget::resolve() {
  glBlitNamedFramebuffer(drawFbo_.id(), resolveFbo_.id(), 0, 0, width_, height_, 0, 0, width_,
                         height_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

void OffscreenTarget::bindResolved() {
  resolveFbo_.bind();
  glViewport(0, 0, width_, height_);
}

void OffscreenTarget::presentTo(GLuint framebuffer, int width, int height) {
  const bool sameSize = width == width_ && height == height_;
  glBlitNamedFramebuffer(resolveFbo_.id(), framebuffer, 0, 0, width_, height_, 0, 0, width, height,
                         GL_COLOR_BUFFER_BIT, sameSize ? GL_NEAREST : GL_LINEAR);
}

RgbImage OffscreenTarget::readResolvedRgb() {
  std::vector<std::uint8_t> bottomUp(size_t(width_) * size_t(height_) * 3);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  gl::readTextureImage(resolved_.id(), 0, GL_RGB, GL_UNSIGNED_BYTE, bottomUp.size(),
                       bottomUp.data());
  RgbImage image(width_, height_);
  const size_t rowBytes = size_t(width_) * 3;
  for (int y = 0; y < height_; ++y) {  // GL rows run bottom-up, PNG rows top-down
    std::memcpy(image.at(0, y), &bottomUp[size_t(height_ - 1 - y) * rowBytes], rowBytes);
  }
  return image;
}

DepthImage OffscreenTarget::readDepth() {
  glBlitNamedFramebuffer(drawFbo_.id(), resolveFbo_.id(), 0, 0, width_, height_, 0, 0, width_,
                         height_, GL_DEPTH_BUFFER_BIT, GL_NEAREST);
  std::vector<float> bottomUp(size_t(width_) * size_t(height_));
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  gl::readTextureImage(resolvedDepth_.id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT,
                       bottomUp.size() * sizeof(float), bottomUp.data());
  DepthImage image{width_, height_, std::vector<float>(bottomUp.size())};
  for (int y = 0; y < height_; ++y) {
    std::memcpy(&image.depth[size_t(y) * size_t(width_)],
                &bottomUp[size_t(height_ - 1 - y) * size_t(width_)],
                size_t(width_) * sizeof(float));
  }
  return image;
}

}  // namespace tellus
