// Google Benchmark micro-benchmarks of what a compute pass costs the thread that issues it: the
// CPU column is the calling thread's CPU time (Google Benchmark's default), which is what the
// bench's render-thread figures count. On a hardware driver a dispatch is queued in
// microseconds; on llvmpipe the "GPU" runs on the same cores and each dispatch and memory
// barrier costs the calling thread a fixed time, which sets a floor under the render-thread
// figures of renderers that do their LOD work in compute passes (GAMeR, GIW, clipmaps: see
// docs/performance.md). The passes dispatched here exit at once (the clipmaps' texel copy over
// no texel), so only the cost of issuing them remains. Run:
// build/release/bench/tellus_micro_benchmarks --benchmark_filter=GlDispatch
#include <benchmark/benchmark.h>

#include <memory>

#include "tellus/gl/buffer.hpp"
#include "tellus/gl/fence.hpp"
#include "tellus/gl/gl_context.hpp"
#include "tellus/gl/program.hpp"
#include "tellus/gl/texture.hpp"

namespace tellus {
namespace {

// One headless context for the process, and an idle pass with what it binds.
struct IdlePass {
  std::unique_ptr<gl::GlContext> context;
  gl::Program program;
  gl::Buffer texels, rects;
  gl::Texture image;

  static IdlePass* get() {
    static IdlePass* pass = [] {
      auto* p = new IdlePass();
      Result<std::unique_ptr<gl::GlContext>> context = gl::createGlContext();
      if (!context) return static_cast<IdlePass*>(nullptr);
      p->context = std::move(context.value());
      if (!gl::buildComputePrograms({{&p->program, "clipmaps/copy_texels.comp"}})) return static_cast<IdlePass*>(nullptr);
      p->texels = gl::Buffer(1024, nullptr);
      p->rects = gl::Buffer(1024, nullptr);
      p->image = gl::Texture::create2DArray(GL_RG32F, 64, 64, 2);
      p->texels.bindBase(GL_SHADER_STORAGE_BUFFER, 0);
      p->rects.bindBase(GL_SHADER_STORAGE_BUFFER, 1);
      glBindImageTexture(0, p->image.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RG32F);
      p->program.use();
      p->program.set("uRectCount", 0);
      p->program.set("uTexelCount", 0);
      glDispatchCompute(1, 1, 1);  // compiled at the first dispatch on llvmpipe
      glFinish();
      return p;
    }();
    return pass;
  }
};

// range(0): work groups (they exit at once); range(1): 1 to follow each dispatch with a
// shader-storage memory barrier.
void BM_GlDispatch(benchmark::State& state) {
  IdlePass* pass = IdlePass::get();
  if (!pass) {
    state.SkipWithError("no GL 4.5 context");
    return;
  }
  const GLuint groups = GLuint(state.range(0));
  const bool barrier = state.range(1) != 0;
  int sinceFinish = 0;
  for (auto _ : state) {
    glDispatchCompute(groups, 1, 1);
    if (barrier) glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    if (++sinceFinish == 64) {  // keep the driver's queue bounded
      state.PauseTiming();
      glFinish();
      sinceFinish = 0;
      state.ResumeTiming();
    }
  }
  glFinish();
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_GlDispatch)->ArgsProduct({{1, 352, 4096}, {0, 1}})->ArgNames({"groups", "barrier"});

}  // namespace
}  // namespace tellus
