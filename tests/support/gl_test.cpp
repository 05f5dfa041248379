#include "support/gl_test.hpp"

#include "tellus/gl/debug_output.hpp"

namespace tellus::test {
namespace {
std::unique_ptr<gl::GlContext>& sharedContext() {
  static std::unique_ptr<gl::GlContext> context;
  return context;
}
std::string& contextError() {
  static std::string error;
  return error;
}
}  // namespace

void GlTest::SetUpTestSuite() {
  if (sharedContext() || !contextError().empty()) return;
  Result<std::unique_ptr<gl::GlContext>> context = gl::createGlContext();
  if (context) {
    sharedContext() = std::move(context.value());
  } else {
    contextError() = context.error().message;
  }
}

gl::GlContext* GlTest::context() {
  return sharedContext().get();
}

void GlTest::SetUp() {
  ASSERT_TRUE(sharedContext()) << "no headless GL 4.5 context: " << contextError();
  gl::checkGlErrors("before test");
  errorsBefore_ = gl::glErrorCount();
}

void GlTest::acceptGlErrorsSoFar() {
  gl::checkGlErrors("acceptGlErrorsSoFar");
  errorsBefore_ = gl::glErrorCount();
}

void GlTest::TearDown() {
  if (!sharedContext()) return;
  gl::checkGlErrors("after test");
  EXPECT_EQ(gl::glErrorCount(), errorsBefore_) << "the test raised GL errors (see the log)";
}

}  // namespace tellus::test
