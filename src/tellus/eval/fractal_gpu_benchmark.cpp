#include "tellus/eval/fractal_gpu_benchmark.hpp"

#include <algorithm>
#include <chrono>

#include "tellus/gl/gpu_wait.hpp"
#include "tellus/render/fractal/fractal_gpu_decoder.hpp"
#include "tellus/tiles/fractal_format.hpp"

namespace tellus {
namespace {

constexpr int kSlots = 32;  // tiles decoded per batch

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

Result<FractalGpuDecodeMeasurement> measureFractalGpuDecode(
    std::span<const std::vector<std::byte>> payloads, TileShape shape, int repeats) {
  if (payloads.empty()) return makeError("no fractal tiles to decode");
  Result<fractal::FractalCode> first = fractal::read(payloads[0], shape);
  if (!first) return first.error();
  Result<FractalGpuDecoder> decoder =
      FractalGpuDecoder::create(geometryForAnyRanges(first.value()), kSlots);
  if (!decoder) return decoder.error();
  gl::Texture heights = gl::Texture::create2DArray(GL_R32F, shape.width, shape.height, kSlots);

  FractalGpuDecodeMeasurement m;
  std::vector<double> totals, gpuOnly;
  for (int r = 0; r < std::max(1, repeats); ++r) {
    double total = 0.0, gpu = 0.0, iterations = 0.0;
    for (std::size_t start = 0; start < payloads.size(); start += kSlots) {
      const std::size_t count = std::min<std::size_t>(kSlots, payloads.size() - start);
      gl::finish();
      const double t0 = now();
      for (std::size_t i = 0; i < count; ++i) {
        Result<fractal::FractalCode> code = fractal::read(payloads[start + i], shape);
        if (!code) return code.error();
        if (Status s = decoder->load(int(i), code.value()); !s) return s.error();
      }
      gl::finish();
      const double t1 = now();
      // As the renderer does: the batch's iterations together, then every tile publishes.
      std::vector<FractalGpuDecoder::IterationRequest> requests;
      for (std::size_t i = 0; i < count; ++i) {
        requests.push_back({int(i), decoder->fullIterations(int(i))});
        iterations += decoder->fullIterations(int(i));
      }
      decoder->iterate(requests);
      for (std::size_t i = 0; i < count; ++i) decoder->publish(int(i), heights, int(i), 1.0f, true);
      gl::finish();
      const double t2 = now();
      total += t2 - t0;
      gpu += t2 - t1;
    }
    totals.push_back(total);
    gpuOnly.push_back(gpu);
    m.meanIterations = iterations / double(payloads.size());
  }
  m.totalSeconds = median(totals);
  m.gpuSeconds = median(gpuOnly);
  return m;
}

}  // namespace tellus
