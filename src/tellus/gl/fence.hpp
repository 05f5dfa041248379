#pragma once
// A GPU fence (glFenceSync) that owns its sync object: everything submitted before it is done
// once passed() says so. passed() only asks (never waits, never counted); wait() blocks until
// the GPU gets there and counts as a wait (gpu_wait.hpp) when it had not yet. Move-only. Needs
// a current GL context.
#include <epoxy/gl.h>

namespace tellus::gl {

class Fence {
 public:
  Fence() = default;
  // A fence after every command submitted so far. Not flushed: it signals once the commands
  // reach the GPU (the frame's end flushes them; wait() flushes).
  static Fence insert();
  ~Fence();
  Fence(Fence&& other) noexcept;
  Fence& operator=(Fence&& other) noexcept;
  Fence(const Fence&) = delete;
  Fence& operator=(const Fence&) = delete;

  bool valid() const { return sync_ != nullptr; }
  // The GPU has finished everything before the fence (an empty fence has passed).
  bool passed();
  // Blocks until passed(); a counted wait when it had not passed yet.
  void wait();

 private:
  explicit Fence(GLsync sync) : sync_(sync) {}
  GLsync sync_ = nullptr;
  bool signalled_ = false;  // seen signalled once: no need to ask again
};

}  // namespace tellus::gl
