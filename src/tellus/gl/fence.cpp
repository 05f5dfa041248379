#include "tellus/gl/fence.hpp"

#include <utility>

#include "tellus/gl/gpu_wait.hpp"

namespace tellus::gl {

Fence Fence::insert() {
  return Fence(glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0));
}

Fence::~Fence() {
  if (sync_) glDeleteSync(sync_);
}

Fence::Fence(Fence&& other) noexcept
    : sync_(std::exchange(other.sync_, nullptr)), signalled_(other.signalled_) {}

Fence& Fence::operator=(Fence&& other) noexcept {
  if (this != &other) {
    if (sync_) glDeleteSync(sync_);
    sync_ = std::exchange(other.sync_, nullptr);
    signalled_ = other.signalled_;
  }
  return *this;
}

bool Fence::passed() {
  if (!sync_ || signalled_) return true;
  const GLenum state = clientWaitSync(sync_, 0, 0);  // asks only
  signalled_ = state == GL_ALREADY_SIGNALED || state == GL_CONDITION_SATISFIED;
  return signalled_;
}

void Fence::wait() {
  if (passed()) return;
  // One second at a time: a lost context would otherwise hang here for ever.
  constexpr GLuint64 kSecondNs = 1'000'000'000;
  for (int tries = 0; tries < 600 && !signalled_; ++tries) {
    const GLenum state = clientWaitSync(sync_, GL_SYNC_FLUSH_COMMANDS_BIT, kSecondNs);
    signalled_ = state == GL_ALREADY_SIGNALED || state == GL_CONDITION_SATISFIED;
    if (state == GL_WAIT_FAILED) break;
  }
  signalled_ = true;  // failed or timed out: the GL is broken, nothing better to wait for
}

}  // namespace tellus::gl
