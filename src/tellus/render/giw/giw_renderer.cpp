#include "tellus/render/giw/giw_renderer.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/vec4.hpp>
#include <spdlog/spdlog.h>


namespace tellus {

Result<std::unique_ptr<GiwRenderer>> GiwRenderer::create(const HeightGrid& grid, const GiwOptions& options) {
  if (Status ok = giw::checkSettings(options.settings); !ok) return ok.error();
  if (grid.width < 2 || grid.height < 2) return makeError("geometry image warping needs a grid of at least 2 x 2 samples");
  std::unique_ptr<GiwRenderer> r(new GiwRenderer());
  r->options_ = options;
  r->grid_ = &grid;
  r->lowestM_ = grid.heightRange().minM;  // once: the view region needs it every frame
  Result<GridMeshShading> shading = GridMeshShading::create(grid, "giw/giw.vert", "GIW");
  if (!shading) return shading.error();
  r->shading_ = std::move(shading.value());
  // The quad mesh of the geometry image: two counter-clockwise triangles a quad.
  const int n = options.settings.size;
  std::vector<std::uint32_t> indices;
  indices.reserve(std::size_t(n - 1) * std::size_t(n - 1) * 6);
  for (int j = 0; j + 1 < n; ++j) {
    for (int i = 0; i + 1 < n; ++i) {
      const std::uint32_t a = std::uint32_t(j * n + i), b = a + 1, c = a + std::uint32_t(n) + 1, d = a + std::uint32_t(n);
      indices.insert(indices.end(), {a, b, c, a, c, d});
    }
  }
  r->indices_ = gl::Buffer(std::span<const std::uint32_t>(indices));
  r->indexCount_ = GLsizei(indices.size());
  for (std::size_t k = 0; k < 2; ++k) {
    r->vertices_[k] = gl::Buffer(std::size_t(n) * std::size_t(n) * sizeof(glm::vec4), nullptr, GL_DYNAMIC_STORAGE_BIT);
    r->arrays_[k] = gl::VertexArray::create();
    const GLuint vao = r->arrays_[k].id();
    glVertexArrayVertexBuffer(vao, 0, r->vertices_[k].id(), 0, GLsizei(sizeof(glm::vec4)));
    glEnableVertexArrayAttrib(vao, 0);
    glVertexArrayAttribFormat(vao, 0, 4, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao, 0, 0);
    r->arrays_[k].setIndexBuffer(r->indices_);
  }
  if (r->shading_.mapStride() == 1) {
    Result<GiwGpuWarp> gpu = GiwGpuWarp::create(n);
    if (!gpu) return gpu.error();
    r->gpu_ = std::make_unique<GiwGpuWarp>(std::move(gpu.value()));
  } else {
    spdlog::info("GIW: the {} x {} grid exceeds one texture: the warp runs on the CPU", grid.width, grid.height);
  }
  return r;
}

void GiwRenderer::prepare(const ViewSetup& view, const RenderSettings& settings) {
  const int next = 1 - current_;
  const float exaggeration = settings.verticalExaggeration;
  if (gpu_) {
    regions_[std::size_t(next)] = giw::viewRegion(*grid_, lowestM_, view, exaggeration);
    gpu_->run(shading_.heights(), *grid_, regions_[std::size_t(next)], LodView::fromSetup(view, exaggeration),
              options_.settings, vertices_[std::size_t(next)]);
  } else {
    giw::GeometryImage& image = images_[std::size_t(next)];
    image = giw::buildGeometryImage(*grid_, lowestM_, view, exaggeration, options_.settings);
    regions_[std::size_t(next)] = image.region;
    // (x, y, height, level) a vertex, the level being how many times denser than the even grid
    // the warp made it (log4 of the density), as the GPU's resample pass writes it.
    std::vector<glm::vec4> packed(image.vertices.size());
    for (std::size_t k = 0; k < packed.size(); ++k) {
      const float level = std::clamp(std::round(std::log2(std::max(image.density[k], 1.0f)) * 0.5f), 0.0f, 7.0f);
      packed[k] = glm::vec4(image.vertices[k], level);
    }
    vertices_[std::size_t(next)].upload(0, packed.size() * sizeof(glm::vec4), packed.data());
    uploadBytes_ = packed.size() * sizeof(glm::vec4);
  }
  current_ = next;
  prepared_ = true;
}

FrameStats GiwRenderer::draw(const ViewSetup& view, const RenderSettings& settings) {
  if (!prepared_) prepare(view, settings);
  prepared_ = false;
  drawImage(current_, view, settings);
  ++framesDrawn_;
  const int n = options_.settings.size;
  FrameStats stats;
  stats.triangles = std::uint64_t(indexCount_) / 3;
  stats.vertices = std::uint64_t(n) * std::uint64_t(n);
  stats.drawCalls = 1;
  stats.uploadBytes = gpu_ ? 0 : uploadBytes_;
  return stats;
}

giw::GeometryImage GiwRenderer::readImage() const {
  const int n = options_.settings.size;
  giw::GeometryImage image;
  image.size = n;
  image.region = regions_[std::size_t(current_)];
  std::vector<glm::vec4> packed(std::size_t(n) * std::size_t(n));
  vertices_[std::size_t(current_)].download(0, packed.size() * sizeof(glm::vec4), packed.data());
  for (const glm::vec4& v : packed) image.vertices.emplace_back(v.x, v.y, v.z);
  return image;
}

bool GiwRenderer::drawPreviousSelection(const ViewSetup& view, const RenderSettings& settings) {
  if (framesDrawn_ < 2) return false;
  drawImage(1 - current_, view, settings);
  return true;
}

void GiwRenderer::drawImage(int which, const ViewSetup& view, const RenderSettings& settings) {
  shading_.draw(view, settings, [&](const gl::Program& program) {
    program.use();
    arrays_[std::size_t(which)].bind();
    glDrawElements(GL_TRIANGLES, indexCount_, GL_UNSIGNED_INT, nullptr);
  });
}

std::vector<std::string> GiwRenderer::frameReport() const {
  const giw::Region& r = regions_[std::size_t(current_)];
  const std::string region = fmt::format("sketch region {:.0f},{:.0f} .. {:.0f},{:.0f} (samples)", r.min.x, r.min.y,
                                         r.max.x, r.max.y);
  if (gpu_) return {region, "importance, warp and resample on the GPU (compute)"};
  const giw::GeometryImage& image = images_[std::size_t(current_)];
  return {region, fmt::format("on the CPU: importance {:.2f} ms, warp {:.2f} ms, resample {:.2f} ms",
                              image.importanceMs, image.warpMs, image.resampleMs)};
}

}  // namespace tellus
