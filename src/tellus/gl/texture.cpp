#include "tellus/gl/texture.hpp"

namespace tellus::gl {

Texture::Texture(GLenum target, int width, int height)
    : target_(target), width_(width), height_(height) {
  GLuint id = 0;
  glCreateTextures(target, 1, &id);
  name_ = GlName<TextureTraits>(id);
}

Texture Texture::create2D(GLenum internalFormat, int width, int height, int levels) {
  Texture texture(GL_TEXTURE_2D, width, height);
  glTextureStorage2D(texture.id(), levels, internalFormat, width, height);
  return texture;
}

Texture Texture::create2DMultisample(GLenum internalFormat, int width, int height, int samples) {
  Texture texture(GL_TEXTURE_2D_MULTISAMPLE, width, height);
  glTextureStorage2DMultisample(texture.id(), samples, internalFormat, width, height, GL_TRUE);
  return texture;
}

Texture Texture::create2DArray(GLenum internalFormat, int width, int height, int layers,
                               int levels) {
  Texture texture(GL_TEXTURE_2D_ARRAY, width, height);
  glTextureStorage3D(texture.id(), levels, internalFormat, width, height, layers);
  return texture;
}

Texture Texture::createCubeMap(GLenum internalFormat, int size, int levels) {
  Texture texture(GL_TEXTURE_CUBE_MAP, size, size);
  glTextureStorage2D(texture.id(), levels, internalFormat, size, size);
  return texture;
}

void Texture::upload2D(int level, int x, int y, int width, int height, GLenum format, GLenum type,
                       const void* data) {
  glTextureSubImage2D(id(), level, x, y, width, height, format, type, data);
}

void Texture::uploadLayer(int level, int layer, int width, int height, GLenum format, GLenum type,
                          const void* data) {
  glTextureSubImage3D(id(), level, 0, 0, layer, width, height, 1, format, type, data);
}

void Texture::setFilter(GLenum minFilter, GLenum magFilter) {
  glTextureParameteri(id(), GL_TEXTURE_MIN_FILTER, GLint(minFilter));
  glTextureParameteri(id(), GL_TEXTURE_MAG_FILTER, GLint(magFilter));
}

void Texture::setWrap(GLenum wrap) {
  glTextureParameteri(id(), GL_TEXTURE_WRAP_S, GLint(wrap));
  glTextureParameteri(id(), GL_TEXTURE_WRAP_T, GLint(wrap));
}

}  // namespace tellus::gl
