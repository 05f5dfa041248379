#include <gtest/gtest.h>

#include <epoxy/gl.h>

#include "support/gl_test.hpp"
#include "tellus/gl/debug_output.hpp"
#include "tellus/gl/gl_info.hpp"

namespace tellus {
namespace {

using ContextTest = test::GlTest;

TEST_F(ContextTest, HeadlessContextIsOpenGl45CoreWithDebugOutput) {
  EXPECT_GE(epoxy_gl_version(), 45);
  GLint profile = 0;
  glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT);
  EXPECT_TRUE(glIsEnabled(GL_DEBUG_OUTPUT));
  const gl::GlInfo info = gl::queryGlInfo();
  EXPECT_FALSE(info.renderer.empty());
  EXPECT_GE(info.maxTextureSize, 8192);
  EXPECT_NE(context()->description().find("EGL"), std::string::npos);
  const std::string report = gl::formatGlInfo(info, context()->description());
  EXPECT_NE(report.find("renderer:"), std::string::npos);
  EXPECT_NE(report.find("max texture size:"), std::string::npos);
}

TEST_F(ContextTest, GlErrorsAreCaughtAndCounted) {
  const std::uint64_t before = gl::glErrorCount();
  glBindBuffer(GL_ARRAY_BUFFER, 987654);  // not a buffer name: GL_INVALID_OPERATION
  gl::checkGlErrors("provoked error");
  EXPECT_GT(gl::glErrorCount(), before);
  acceptGlErrorsSoFar();
}

}  // namespace
}  // namespace tellus
