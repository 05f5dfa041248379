#pragma once
// GlTest: a fixture for tests that need a headless GL 4.5 context. One EGL context is shared by
// all tests of the process; every test fails if it raised a GL error (debug output or
// glGetError()).
#include <memory>

#include <gtest/gtest.h>

#include "tellus/gl/gl_context.hpp"

namespace tellus::test {

class GlTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite();
  void SetUp() override;
  void TearDown() override;

  static gl::GlContext* context();
  // For tests that provoke GL errors on purpose: accepts the errors raised so far.
  void acceptGlErrorsSoFar();

 private:
  std::uint64_t errorsBefore_ = 0;
};

}  // namespace tellus::test
