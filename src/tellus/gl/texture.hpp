#pragma once
// GL texture object with immutable storage (DSA). Needs a current GL 4.5 context.
#include "tellus/gl/gl_name.hpp"

namespace tellus::gl {

struct TextureTraits {
  static void destroy(GLuint id) { glDeleteTextures(1, &id); }
};

class Texture {
 public:
  Texture() = default;

  // A 2D texture (or multisample 2D when samples > 1) of `levels` mip levels.
  static Texture create2D(GLenum internalFormat, int width, int height, int levels = 1);
  static Texture create2DMultisample(GLenum internalFormat, int width, int height, int samples);
  // A 2D array texture of `layers` layers.
  static Texture create2DArray(GLenum internalFormat, int width, int height, int layers,
                               int levels = 1);

  // A cube map of `levels` mip levels, faces `size` texels a side (uploadLayer: layer = face,
  // 0..5 for +X, -X, +Y, -Y, +Z, -Z).
  static Texture createCubeMap(GLenum internalFormat, int size, int levels = 1);

  // Uploads a width x height block at (x, y) of mip level `level` (and array layer `layer`).
  void upload2D(int level, int x, int y, int width, int height, GLenum format, GLenum type,
                const void* data);
  void uploadLayer(int level, int layer, int width, int height, GLenum format, GLenum type,
                   const void* data);
  void setFilter(GLenum minFilter, GLenum magFilter);
  void setWrap(GLenum wrap);
  void bindUnit(GLuint unit) const { glBindTextureUnit(unit, id()); }

  GLuint id() const { return name_.id(); }
  int width() const { return width_; }
  int height() const { return height_; }
  GLenum target() const { return target_; }

 private:
  Texture(GLenum target, int width, int height);
  GlName<TextureTraits> name_;
  GLenum target_ = 0;
  int width_ = 0;
  int height_ = 0;
};

}  // namespace tellus::gl
