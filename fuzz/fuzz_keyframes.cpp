// libFuzzer target: the keyframe JSON reader (tellus bench --path, tellus view --path) on
// arbitrary text, and the path it makes sampled and evaluated anywhere in time: parsing must
// fail with a message or give a path whose every camera is finite.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "tellus/eval/camera_path.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  tellus::Result<tellus::CameraPath> path = tellus::parseCameraPath(text, "fuzz.json");
  if (!path) return 0;
  const double start = path->keyframes().front().timeS;
  for (const double t : {start - 1.0, start, start + 0.37 * path->durationS(),
                         start + path->durationS(), start + 2.0 * path->durationS() + 1.0}) {
    const tellus::Camera c = path->at(t);
    const bool finite = std::isfinite(c.position.x) && std::isfinite(c.position.y) &&
                        std::isfinite(c.position.z) && std::isfinite(c.yawDeg) &&
                        std::isfinite(c.pitchDeg) && std::isfinite(c.fovYDeg);
    if (!finite) std::abort();  // a validated path must never give a non-finite camera
  }
  (void)path->sample(7);
  return 0;
}
