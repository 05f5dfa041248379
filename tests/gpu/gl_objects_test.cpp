// The RAII wrappers own exactly one GL object each: moves transfer it, destruction deletes it.
#include <array>
#include <vector>

#include <gtest/gtest.h>

#include "support/gl_test.hpp"
#include "tellus/gl/buffer.hpp"
#include "tellus/gl/framebuffer.hpp"
#include "tellus/gl/program.hpp"
#include "tellus/gl/query.hpp"
#include "tellus/gl/shader_library.hpp"
#include "tellus/gl/texture.hpp"
#include "tellus/gl/vertex_array.hpp"
#include "tellus/render/output/offscreen_target.hpp"
#include "tellus/render/reference/reference_renderer.hpp"

namespace tellus {
namespace {

using GlObjectsTest = test::GlTest;

TEST_F(GlObjectsTest, BufferRoundTripsAndOwnsItsName) {
  const std::array<float, 4> data = {1.0f, 2.5f, -3.0f, 4.0f};
  GLuint name = 0;
  {
    gl::Buffer buffer(std::span<const float>(data), GL_DYNAMIC_STORAGE_BIT);
    name = buffer.id();
    EXPECT_TRUE(glIsBuffer(name));
    const float replacement = 9.0f;
    buffer.upload(sizeof(float), sizeof(float), &replacement);
    std::array<float, 4> back{};
    buffer.download(0, sizeof(back), back.data());
    EXPECT_EQ(back, (std::array<float, 4>{1.0f, 9.0f, -3.0f, 4.0f}));

    gl::Buffer moved = std::move(buffer);
    EXPECT_EQ(moved.id(), name);
    EXPECT_EQ(buffer.id(), 0u);  // NOLINT: the moved-from state is part of the contract
    EXPECT_TRUE(glIsBuffer(name));
  }
  EXPECT_FALSE(glIsBuffer(name));  // deleted with its last owner
}

TEST_F(GlObjectsTest, TextureUploadsAndReadsBack) {
  gl::Texture texture = gl::Texture::create2D(GL_R32F, 3, 2);
  const std::vector<float> values = {1, 2, 3, 4, 5, 6};
  texture.upload2D(0, 0, 0, 3, 2, GL_RED, GL_FLOAT, values.data());
  std::vector<float> back(6);
  glGetTextureImage(texture.id(), 0, GL_RED, GL_FLOAT, GLsizei(back.size() * sizeof(float)),
                    back.data());
  EXPECT_EQ(back, values);
  const GLuint name = texture.id();
  texture = gl::Texture::create2D(GL_RGBA8, 4, 4);  // move-assignment deletes the old texture
  EXPECT_FALSE(glIsTexture(name));
}

TEST_F(GlObjectsTest, FramebufferReportsCompleteness) {
  gl::Framebuffer fbo = gl::Framebuffer::create();
  EXPECT_FALSE(fbo.checkComplete());  // nothing attached
  gl::Texture colour = gl::Texture::create2D(GL_RGBA8, 8, 8);
  fbo.attach(GL_COLOR_ATTACHMENT0, colour);
  EXPECT_TRUE(fbo.checkComplete());
}

TEST_F(GlObjectsTest, QueriesMeasureADraw) {
  HeightGrid grid(65, 65);
  grid.spacingXM = grid.spacingYM = 10.0;
  Result<ReferenceRenderer> renderer = ReferenceRenderer::create(grid);
  ASSERT_TRUE(renderer) << renderer.error().message;
  Result<OffscreenTarget> target = OffscreenTarget::create(64, 64, 1);
  ASSERT_TRUE(target) << target.error().message;
  Camera camera;
  camera.position = {320.0, 320.0, 500.0};
  camera.pitchDeg = -90.0;
  const ViewSetup view = ViewSetup::create(camera, grid.worldBounds(), 64, 64);
  gl::Query timer = gl::Query::create(GL_TIME_ELAPSED);
  gl::Query primitives = gl::Query::create(GL_PRIMITIVES_GENERATED);
  target->begin({0, 0, 0});
  timer.begin();
  primitives.begin();
  renderer->draw(view, RenderSettings{});
  primitives.end();
  timer.end();
  glFinish();
  EXPECT_TRUE(timer.available());
  EXPECT_GT(timer.result(), 0u);
  EXPECT_LT(timer.result(), 10'000'000'000ull);  // nanoseconds: far less than 10 s
  EXPECT_EQ(primitives.result(), 64u * 64u * 2u);
}

TEST_F(GlObjectsTest, ShaderLibraryExpandsIncludesWithLineDirectives) {
  Result<gl::ExpandedShader> shader = gl::loadShader("terrain/terrain.frag");
  ASSERT_TRUE(shader) << shader.error().message;
  // + shading.glsl, the imagery.glsl it includes, heightfield.glsl and lod_colours.glsl
  ASSERT_EQ(shader->files.size(), 5u);
  EXPECT_EQ(shader->files[0], "terrain/terrain.frag");
  EXPECT_EQ(shader->files[1], "common/shading.glsl");
  EXPECT_EQ(shader->files[2], "common/imagery.glsl");
  EXPECT_NE(shader->source.find("vec3 shadeTerrain("), std::string::npos);
  EXPECT_NE(shader->source.find("#line 1 1\n"), std::string::npos);  // shading.glsl starts
  EXPECT_NE(shader->source.find("#line 3 0\n"), std::string::npos);  // back in terrain.frag
  EXPECT_EQ(shader->source.find("#include"), std::string::npos);
  EXPECT_EQ(shader->source.rfind("#version 450 core", 0), 0u);
  Result<gl::ExpandedShader> missing = gl::loadShader("terrain/nope.frag");
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("terrain/nope.frag"), std::string::npos);
}

TEST_F(GlObjectsTest, ProgramsLinkAndExposeUniforms) {
  Result<gl::Program> program = gl::Program::fromFiles(
      {{GL_VERTEX_SHADER, "terrain/reference.vert"}, {GL_FRAGMENT_SHADER, "terrain/terrain.frag"}});
  ASSERT_TRUE(program) << program.error().message;
  EXPECT_GE(program->location("uViewProjection"), 0);
  EXPECT_GE(program->location("uSunDirection"), 0);
  EXPECT_EQ(program->location("uNoSuchUniform"), -1);
}

}  // namespace
}  // namespace tellus
