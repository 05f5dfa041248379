// A store streamed over HTTP from a stock server (lighttpd on 127.0.0.1): the rings renderer
// draws it exactly as from disk, and when the server dies mid-stream the tiles that do not
// arrive leave a coarser surface (their resident ancestors), never a hole or a crash, and the
// errors name the URL and the cause.
#include <cstdlib>

#include <gtest/gtest.h>

#include "support/gl_test.hpp"
#include "support/http_server.hpp"
#include "support/terrain_fixtures.hpp"
#include "support/test_support.hpp"
#include "tellus/dem/terrain_generator.hpp"
#include "tellus/render/rings/rings_renderer.hpp"
#include "tellus/tiles/http_byte_source.hpp"

namespace tellus {
namespace {

namespace fs = std::filesystem;
using test::kSentinel;

class HttpStreamingTest : public test::GlTest {
 protected:
  static void SetUpTestSuite() {
    test::GlTest::SetUpTestSuite();
    // Fail fast once the server is gone: one retry, 10 ms back-off, 1 s timeouts.
    ::setenv("TELLUS_HTTP_RETRIES", "1", 1);
    ::setenv("TELLUS_HTTP_BACKOFF_MS", "10", 1);
    ::setenv("TELLUS_HTTP_CONNECT_MS", "1000", 1);
    TerrainParams params;
    params.size = 513;
    params.seed = 5;
    params.spacingM = 200.0;
    folder_ = new fs::path(test::processFixtureDir("http-store"));
    test::GeneratedStore built = test::buildGeneratedStore(params, *folder_, 32);
    ASSERT_TRUE(built.store);
    store_ = new std::shared_ptr<const TileStore>(built.store);
    grid_ = new HeightGrid(std::move(built.level0));
  }
  static void TearDownTestSuite() {
    delete store_;
    delete grid_;
    delete folder_;
  }
  static fs::path folder() { return *folder_; }
  static fs::path* folder_;
  static HeightGrid* grid_;
  static std::shared_ptr<const TileStore>* store_;
};
HeightGrid* HttpStreamingTest::grid_ = nullptr;
fs::path* HttpStreamingTest::folder_ = nullptr;
std::shared_ptr<const TileStore>* HttpStreamingTest::store_ = nullptr;

// Low over the terrain looking north, moving north along `t` in [0, 1].
Camera pathCamera(const HeightGrid& grid, double t) {
  const Aabb b = grid.worldBounds();
  Camera camera;
  camera.position = {0.5 * (b.min.x + b.max.x), b.min.y + (0.1 + 0.6 * t) * (b.max.y - b.min.y),
                     b.max.z + 1500.0};
  camera.yawDeg = 10.0;
  camera.pitchDeg = -25.0;
  return camera;
}

TEST_F(HttpStreamingTest, DrawsTheStoreExactlyAsFromDisk) {
  std::string why;
  std::optional<test::LocalHttpServer> server = test::LocalHttpServer::start(folder(), why);
  ASSERT_TRUE(server) << why;
  Result<std::shared_ptr<TileStore>> remote = TileStore::open(server->url("terrain.tstore"));
  ASSERT_TRUE(remote) << remote.error().message;
  EXPECT_EQ(remote.value()->fileBytes(), (*store_)->fileBytes());
  RingsOptions options;
  options.waitForTiles = true;
  auto local = test::createRings(*store_, options);
  auto streamed = test::createRings(remote.value(), options);
  ASSERT_TRUE(local && streamed);
  for (const double t : {0.0, 0.5, 1.0}) {
    const Camera camera = pathCamera(*grid_, t);
    const test::RenderedFrame a = test::renderFrame(*local, grid_->worldBounds(), camera, 320, 180);
    const test::RenderedFrame b = test::renderFrame(*streamed, grid_->worldBounds(), camera, 320, 180);
    EXPECT_EQ(a.colour.pixels, b.colour.pixels) << "t " << t;
  }
  const auto& http = dynamic_cast<const HttpByteSource&>(remote.value()->source());
  EXPECT_GT(http.requests(), 10u);
  EXPECT_EQ(http.retries(), 0u);  // one request a read on a healthy server
}

TEST_F(HttpStreamingTest, AServerKilledMidStreamLeavesACoarserSurfaceNotAHole) {
  std::string why;
  std::optional<test::LocalHttpServer> server = test::LocalHttpServer::start(folder(), why);
  ASSERT_TRUE(server) << why;
  Result<std::shared_ptr<TileStore>> remote = TileStore::open(server->url("terrain.tstore"));
  ASSERT_TRUE(remote) << remote.error().message;
  RingsOptions streaming;
  streaming.gpuSlots = 24;  // small: moving on needs new tiles
  auto renderer = test::createRings(remote.value(), streaming);
  RingsOptions settled;
  settled.waitForTiles = true;
  auto reference = test::createRings(*store_, settled);
  ASSERT_TRUE(renderer && reference);
  constexpr int kFrames = 40;
  int framesAfterKill = 0;
  for (int frame = 0; frame < kFrames; ++frame) {
    if (frame == 8) server->kill();  // mid-stream: tiles are still wanted
    const Camera camera = pathCamera(*grid_, double(frame) / (kFrames - 1));
    const test::RenderedFrame drawn =
        test::renderFrame(*renderer, grid_->worldBounds(), camera, 320, 180);
    const test::RenderedFrame full =
        test::renderFrame(*reference, grid_->worldBounds(), camera, 320, 180);
    // The terrain covers the same pixels (a coarser surface may shift its silhouette by a few
    // pixels): no hole where tiles are missing.
    const double drawnCover = 1.0 - test::foregroundStats(drawn.colour, kSentinel).fraction;
    const double fullCover = 1.0 - test::foregroundStats(full.colour, kSentinel).fraction;
    EXPECT_NEAR(drawnCover, fullCover, 0.01) << "frame " << frame;
    if (frame >= 8) ++framesAfterKill;
  }
  EXPECT_EQ(framesAfterKill, kFrames - 8);
  // After the kill the renderer drew from what it had: tiles it wanted did not arrive.
  EXPECT_GT(renderer->lastFrame().fallbackPatches + renderer->lastFrame().misses, 0);
  // A read now names the URL and the cause.
  std::vector<float> heights(remote.value()->layout().tileShape().sampleCount());
  Status read = remote.value()->readTileMetres({0, 5, 5}, heights);
  ASSERT_FALSE(read);
  EXPECT_NE(read.error().message.find(server->url("terrain.tstore")), std::string::npos)
      << read.error().message;
  EXPECT_NE(read.error().message.find("after 2 tries"), std::string::npos) << read.error().message;
}

TEST_F(HttpStreamingTest, RefusesMissingFilesAndServersWithoutRanges) {
  std::string why;
  std::optional<test::LocalHttpServer> server =
      test::LocalHttpServer::start(test::freshTestDir(), why);
  ASSERT_TRUE(server) << why;
  Result<std::shared_ptr<TileStore>> missing = TileStore::open(server->url("nothing.tstore"));
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("HTTP 404"), std::string::npos) << missing.error().message;
  // Python's http.server answers a range request with the whole file (200).
  const fs::path dir = test::freshTestDir();
  fs::copy_file(folder() / "terrain.tstore", dir / "terrain.tstore");
  std::optional<test::LocalHttpServer> noRanges = test::LocalHttpServer::startWithoutRanges(dir, why);
  ASSERT_TRUE(noRanges) << why;
  Result<std::shared_ptr<TileStore>> whole = TileStore::open(noRanges->url("terrain.tstore"));
  ASSERT_FALSE(whole);
  EXPECT_NE(whole.error().message.find("does not answer range requests"), std::string::npos)
      << whole.error().message;
  server->kill();
  Result<std::shared_ptr<TileStore>> gone = TileStore::open(server->url("nothing.tstore"));
  ASSERT_FALSE(gone);
  EXPECT_NE(gone.error().message.find("connect"), std::string::npos) << gone.error().message;
}

}  // namespace
}  // namespace tellus
