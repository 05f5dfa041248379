// The public API (include/tellus/tellus.hpp) on a generated store: its facts are the store's,
// a view draws exactly what the renderer it names draws through the library's own calls, its
// options reach the renderer, everything it cannot do is a clear error (never a crash: a thread
// without a GL context included), and the glTF export writes a binary glTF.
#include <gtest/gtest.h>

#include <fstream>
#include <thread>

#include "support/gl_test.hpp"
#include "support/terrain_fixtures.hpp"
#include "support/test_support.hpp"
#include "tellus/core/camera.hpp"
#include "tellus/render/output/snapshot.hpp"
#include "tellus/render/registry/renderer_registry.hpp"
#include "tellus/tellus.hpp"

namespace tellus {
namespace {

class PublicApiTest : public test::GlTest {
 protected:
  // 257 x 257 samples, 100 m apart, in 32-cell tiles.
  static void SetUpTestSuite() {
    test::GlTest::SetUpTestSuite();
    TerrainParams params;
    params.size = 257;
    params.seed = 5;
    params.spacingM = 100.0;
    params.reliefM = 1500.0;
    const auto dir = test::processFixtureDir("public-api");
    std::filesystem::create_directories(test::testOutputDir() / "public-api");  // the pictures
    test::GeneratedStore built = test::buildGeneratedStore(params, dir, 32);
    ASSERT_TRUE(built.store);
    storePath_ = new std::string((dir / "terrain.tstore").string());
  }
  static void TearDownTestSuite() {
    delete storePath_;
    storePath_ = nullptr;
  }

  static Terrain openTerrain() {
    auto terrain = Terrain::open(*storePath_);
    EXPECT_TRUE(terrain) << terrain.error().message;
    return std::move(terrain.value());
  }

  static std::string* storePath_;
};
std::string* PublicApiTest::storePath_ = nullptr;

TEST_F(PublicApiTest, OpensAStoreAndReportsWhatItHolds) {
  const Terrain terrain = openTerrain();
  auto store = TileStore::open(*storePath_);
  ASSERT_TRUE(store);
  const StoreMetadata& metadata = store.value()->metadata();
  const TerrainFacts& facts = terrain.facts();
  EXPECT_EQ(facts.source, *storePath_);
  EXPECT_EQ(facts.samplesX, 257);
  EXPECT_EQ(facts.samplesY, 257);
  EXPECT_EQ(facts.levels, metadata.layout.levelCount());
  EXPECT_DOUBLE_EQ(facts.spacingXM, metadata.spacingXM);  // ground spacing: about 100 m in UTM
  EXPECT_NEAR(facts.spacingXM, 100.0, 0.1);
  EXPECT_DOUBLE_EQ(facts.widthM, 256 * metadata.spacingXM);
  EXPECT_DOUBLE_EQ(facts.depthM, 256 * metadata.spacingYM);
  EXPECT_EQ(facts.minHeightM, metadata.minHeightM);
  EXPECT_EQ(facts.maxHeightM, metadata.maxHeightM);
  EXPECT_LT(facts.minHeightM, facts.maxHeightM);
  EXPECT_FALSE(facts.crs.empty());
}

TEST_F(PublicApiTest, ListsTheFlatRenderersWithTheirOptions) {
  const std::vector<RendererInfo> list = listRenderers();
  std::vector<std::string> names;
  for (const RendererInfo& info : list) names.push_back(info.name);
  for (const RendererEntry* entry : rendererTable()) {
    const bool flat = entry->world == RendererWorld::Flat &&
                      (entry->source == RendererSource::HeightGrid ||
                       entry->source == RendererSource::TileStore);
    EXPECT_EQ(std::ranges::count(names, std::string(entry->name)), flat ? 1 : 0) << entry->name;
  }
  const auto rings = std::ranges::find(list, std::string("rings"), &RendererInfo::name);
  ASSERT_NE(rings, list.end());
  const auto slots = std::ranges::find(rings->options, std::string("rings-gpu-slots"),
                                       &RendererOptionInfo::name);
  ASSERT_NE(slots, rings->options.end());
  EXPECT_FALSE(slots->help.empty());
}

// Pixel for pixel what the library's own makeRenderer + renderSnapshot draw from the camera
// overviewCamera gives: the API adds nothing and loses nothing.
TEST_F(PublicApiTest, DrawsWhatTheNamedRendererDraws) {
  const Terrain terrain = openTerrain();
  auto store = TileStore::open(*storePath_);
  ASSERT_TRUE(store);
  auto grid = readStoreLevel(*store.value(), 0);
  ASSERT_TRUE(grid);
  for (const std::string name : {"reference", "rings", "roam"}) {
    SCOPED_TRACE(name);
    ViewSettings settings;
    settings.width = 320;
    settings.height = 180;
    auto view = TerrainView::create(terrain, name, settings);
    ASSERT_TRUE(view) << view.error().message;
    EXPECT_EQ(view.value().renderer(), name);
    const Viewpoint viewpoint = overviewOf(terrain, 16.0 / 9.0, 30.0);
    FrameReport report;
    auto picture = view.value().draw(viewpoint, &report);
    ASSERT_TRUE(picture) << picture.error().message;
    ASSERT_EQ(picture.value().width, 320);
    ASSERT_EQ(picture.value().height, 180);
    EXPECT_GT(report.triangles, 0u);

    const Aabb bounds = grid.value().worldBounds();
    const Camera camera = overviewCamera(bounds, 16.0 / 9.0, 40.0, -35.0, 30.0);
    EXPECT_DOUBLE_EQ(viewpoint.x, camera.position.x);
    EXPECT_DOUBLE_EQ(viewpoint.z, camera.position.z);
    RendererInputs inputs;
    inputs.grid = &grid.value();
    inputs.store = store.value();
    inputs.waitForTiles = true;
    auto renderer = makeRenderer(name, inputs);
    ASSERT_TRUE(renderer) << renderer.error().message;
    SnapshotOptions snapshot;
    snapshot.width = 320;
    snapshot.height = 180;
    FrameStats stats;
    auto expected = renderSnapshot(*renderer.value(), bounds, camera, snapshot, &stats);
    ASSERT_TRUE(expected);
    EXPECT_EQ(report.triangles, stats.triangles);
    EXPECT_TRUE(picture.value().rgb == expected.value().pixels);

    const auto png = test::testOutputDir() / "public-api" / (name + ".png");
    ASSERT_TRUE(picture.value().savePng(png.string()));
    EXPECT_GT(std::filesystem::file_size(png), 1000u);
  }
}

TEST_F(PublicApiTest, OptionsReachTheRenderer) {
  const Terrain terrain = openTerrain();
  const Viewpoint viewpoint = overviewOf(terrain, 16.0 / 9.0);
  std::vector<std::uint64_t> triangles;
  for (const char* count : {"2", "4"}) {
    ViewSettings settings;
    settings.width = 160;
    settings.height = 90;
    settings.options["rings-count"] = count;
    auto view = TerrainView::create(terrain, "rings", settings);
    ASSERT_TRUE(view) << view.error().message;
    FrameReport report;
    ASSERT_TRUE(view.value().draw(viewpoint, &report));
    triangles.push_back(report.triangles);
  }
  EXPECT_NE(triangles[0], triangles[1]);
}

TEST_F(PublicApiTest, WhatItCannotDoIsAClearError) {
  const Terrain terrain = openTerrain();
  const auto refused = [&](const std::string& name, RendererOptions options = {}) {
    ViewSettings settings;
    settings.options = std::move(options);
    auto view = TerrainView::create(terrain, name, settings);
    EXPECT_FALSE(view) << name;
    return view ? std::string() : view.error().message;
  };
  EXPECT_NE(refused("no-such").find("renderers: reference"), std::string::npos);
  // Globe renderers draw other inputs: not offered.
  EXPECT_NE(refused("ringo").find("unknown renderer 'ringo'"), std::string::npos);
  const std::string unknownOption = refused("rings", {{"rings-colour", "red"}});
  EXPECT_NE(unknownOption.find("no option 'rings-colour'"), std::string::npos) << unknownOption;
  EXPECT_NE(unknownOption.find("rings-gpu-slots"), std::string::npos) << unknownOption;
  const std::string outOfRange = refused("rings", {{"rings-count", "-3"}});
  EXPECT_NE(outOfRange.find("rings-count: '-3' is not a whole number in"), std::string::npos)
      << outOfRange;
  EXPECT_NE(refused("rings", {{"rings-count", "4x"}}).find("'4x'"), std::string::npos);

  ViewSettings tooLarge;
  tooLarge.width = 100000;
  EXPECT_FALSE(TerrainView::create(terrain, "rings", tooLarge));

  auto view = TerrainView::create(terrain, "reference");
  ASSERT_TRUE(view);
  Viewpoint bad = overviewOf(terrain, 1.0);
  bad.pitchDeg = 120.0;
  auto picture = view.value().draw(bad);
  ASSERT_FALSE(picture);
  EXPECT_NE(picture.error().message.find("pitch"), std::string::npos) << picture.error().message;

  // A thread without a current context gets an error, not a crash in the GL loader.
  std::string withoutContext;
  std::thread([&] {
    auto made = TerrainView::create(terrain, "reference");
    withoutContext = made ? std::string("made") : made.error().message;
  }).join();
  EXPECT_NE(withoutContext.find("needs a current OpenGL context"), std::string::npos)
      << withoutContext;

  const auto notAStore = test::freshTestDir() / "not-a-store.tstore";
  std::ofstream(notAStore) << "hello";
  auto opened = Terrain::open(notAStore.string());
  ASSERT_FALSE(opened);
  EXPECT_NE(opened.error().message.find("not-a-store.tstore"), std::string::npos);
}

TEST_F(PublicApiTest, ExportsABinaryGltf) {
  const Terrain terrain = openTerrain();
  const auto glb = test::freshTestDir() / "terrain.glb";
  MeshExportSettings settings;
  settings.maxErrorM = 5.0;
  auto summary = exportGlb(terrain, glb.string(), settings);
  ASSERT_TRUE(summary) << summary.error().message;
  EXPECT_GT(summary.value().triangles, 100u);
  EXPECT_LE(summary.value().maxErrorM, 5.0);
  EXPECT_EQ(summary.value().bytes, std::filesystem::file_size(glb));
  std::ifstream file(glb, std::ios::binary);
  char magic[4] = {};
  file.read(magic, 4);
  EXPECT_EQ(std::string(magic, 4), "glTF");

  settings.maxErrorM = -1.0;
  EXPECT_FALSE(exportGlb(terrain, (glb.parent_path() / "never.glb").string(), settings));
  EXPECT_FALSE(std::filesystem::exists(glb.parent_path() / "never.glb"));
}

}  // namespace
}  // namespace tellus
