// Material stacks (seed 003): columns are checked, memory is counted against dense voxels, and
// the level-of-detail aggregation follows each rule of its heuristic (the density rules are
// tested with the pipeline: quadrangulation_test.cpp).
#include <cstring>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>

#include "support/store_surgery.hpp"
#include "support/test_support.hpp"

#include "tellus/formats/stacks/material_stack.hpp"
#include "tellus/formats/stacks/stack_aggregation.hpp"
#include "tellus/dem/geotiff_writer.hpp"
#include "tellus/formats/stacks/stack_file.hpp"
#include "tellus/formats/stacks/stack_generator.hpp"
#include "tellus/lod/stacks/stack_sky_heights.hpp"

namespace tellus {
namespace {

constexpr StackMaterial kRock = 1, kSoil = 2, kSand = 3, kGrass = 4;

using Column = std::vector<StackLayer>;

std::vector<StackLayer> aggregate(const std::vector<Column>& columns) {
  std::vector<std::span<const StackLayer>> spans(columns.begin(), columns.end());
  return aggregateColumns(spans);
}

TEST(MaterialStack, ColumnsAreCheckedLayerByLayer) {
  EXPECT_TRUE(checkStackColumn(Column{{0, 5, kRock}, {5, 6, kSoil}, {9, 12, kRock}}));
  EXPECT_TRUE(checkStackColumn(Column{}));
  const auto why = [](const Column& c) { return checkStackColumn(c).error().message; };
  EXPECT_NE(why({{0, 5, kAir}}).find("air is the gap"), std::string::npos);
  EXPECT_NE(why({{3, 3, kRock}}).find("not above its bottom"), std::string::npos);
  EXPECT_NE(why({{0, 5, kRock}, {4, 6, kSoil}}).find("layer 1 starts at 4 m"), std::string::npos);
  Result<StackTerrain> bad = StackTerrain::fromColumns(2, 1, 2.0, {{{0, 1, kRock}}, {{2, 1, kRock}}});
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("column (1, 0)"), std::string::npos) << bad.error().message;
  EXPECT_FALSE(StackTerrain::fromColumns(2, 2, 2.0, {{}, {}, {}}));  // three columns for four
  EXPECT_FALSE(StackTerrain::fromArrays(1, 1, 2.0, {0, 2}, {{0, 1, kRock}}));  // offsets beyond
}

TEST(MaterialStack, MemoryAgainstTheDenseVoxelGrid) {
  // 4 x 4 columns of ground to 100 m with an arch 60..70 m: 2 layers a column.
  std::vector<Column> columns(16, Column{{0, 50, kRock}, {60, 70, kRock}});
  Result<StackTerrain> t = StackTerrain::fromColumns(4, 4, 2.0, columns);
  ASSERT_TRUE(t);
  EXPECT_EQ(t->layerCount(), 32u);
  EXPECT_FLOAT_EQ(t->topM(), 70.0f);
  EXPECT_EQ(t->bytes(), 32 * sizeof(StackLayer) + 17 * sizeof(std::uint32_t));
  EXPECT_EQ(t->denseVoxelBytes(2.0), 16u * 35u);
}

TEST(StackAggregation, ADominantMaterialIsChosen) {
  // Three rock, one soil between 0 and 10 m: rock.
  const auto out = aggregate({{{0, 10, kRock}}, {{0, 10, kRock}}, {{0, 10, kRock}}, {{0, 10, kSoil}}});
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0], (StackLayer{0, 10, kRock}));
}

TEST(StackAggregation, ATieTakesTheMaterialDominantNextToIt) {
  // 0..10 all rock; 10..12 two rock, two sand; 12..20 air everywhere. Below is rock: rock.
  const auto out = aggregate({{{0, 12, kRock}}, {{0, 12, kRock}},
                              {{0, 10, kRock}, {10, 12, kSand}}, {{0, 10, kRock}, {10, 12, kSand}},
                              });
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0], (StackLayer{0, 12, kRock}));
}

TEST(StackAggregation, ATieBetweenWhatIsBelowAndWhatIsAboveIsSplit) {
  // A ragged surface: two columns to 10 m, two to 12 m. 10..12 ties rock and air, rock below
  // and the sky above: the surface at the mean, 11 m.
  const auto out = aggregate({{{0, 10, kRock}}, {{0, 12, kRock}}, {{0, 10, kRock}}, {{0, 12, kRock}}});
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0], (StackLayer{0, 11, kRock}));
  // Under an overhang: 20..30 ties soil (two columns) and rock (two): soil dominates below,
  // rock above: split.
  const auto split = aggregate({{{0, 20, kSoil}, {20, 30, kSoil}, {30, 40, kRock}},
                                {{0, 20, kSoil}, {20, 30, kSoil}, {30, 40, kRock}},
                                {{0, 20, kSoil}, {20, 30, kRock}, {30, 40, kRock}},
                                {{0, 20, kSoil}, {20, 30, kRock}, {30, 40, kRock}}});
  ASSERT_EQ(split.size(), 2u);
  EXPECT_EQ(split[0], (StackLayer{0, 25, kSoil}));
  EXPECT_EQ(split[1], (StackLayer{25, 40, kRock}));
}

TEST(StackAggregation, ASurfaceKeepsItsHeightAndItsOwnMaterial) {
  // Rock to 10 m, soil to 11, 11.5, 12, 12.5 m, 0.25 m of grass on each: at every height of
  // the top metre the four columns hold different solids (grass in one, soil in another) or
  // air. Deciding solid against air first keeps the surface at its median height (the ties
  // split at the mean), and the surface takes its own material, grass, not the soil under it.
  const auto column = [](float soilTop) {
    return Column{{0, 10, kRock}, {10, soilTop, kSoil}, {soilTop, soilTop + 0.25f, kGrass}};
  };
  const auto out = aggregate({column(11.0f), column(11.5f), column(12.0f), column(12.5f)});
  ASSERT_GE(out.size(), 2u);
  EXPECT_EQ(out.back().material, kGrass);
  EXPECT_NEAR(out.back().topM, 12.0f, 0.3f);  // the median of 11.25 .. 12.75
  EXPECT_EQ(out.front(), (StackLayer{0, 10, kRock}));
}

TEST(StackAggregation, TheNeighbourhoodWidensUntilATiedMaterialDominates) {
  // 0..10 sand everywhere; 10..12 ties rock and soil; 12..14 air everywhere (a cave); 14..20
  // rock everywhere (its roof). Next to the tie are sand and air, neither tied; a segment
  // further, rock dominates above (and nothing is below): rock.
  const auto out = aggregate({{{0, 10, kSand}, {10, 12, kRock}, {14, 20, kRock}},
                              {{0, 10, kSand}, {10, 12, kRock}, {14, 20, kRock}},
                              {{0, 10, kSand}, {10, 12, kSoil}, {14, 20, kRock}},
                              {{0, 10, kSand}, {10, 12, kSoil}, {14, 20, kRock}}});
  ASSERT_EQ(out.size(), 3u);
  EXPECT_EQ(out[0], (StackLayer{0, 10, kSand}));
  EXPECT_EQ(out[1], (StackLayer{10, 12, kRock}));
  EXPECT_EQ(out[2], (StackLayer{14, 20, kRock}));
}

TEST(StackAggregation, WithoutAnswerTheThickestTiedMaterialWins) {
  // One segment only, a 2 : 2 tie of rock and soil; nothing below, the sky above (air, not
  // tied): the column is exhausted; soil is thicker over the four stacks? Equal here: the
  // thickness ties too, so the lower id (rock) wins.
  const auto out = aggregate({{{0, 10, kRock}}, {{0, 10, kRock}}, {{0, 10, kSoil}}, {{0, 10, kSoil}}});
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].material, kRock);
  // Two stacks only (the grid's edge): rock against soil, soil thicker elsewhere in the pair.
  const auto edge = aggregate({{{0, 10, kRock}}, {{0, 10, kSoil}, {30, 40, kSoil}}});
  EXPECT_EQ(edge.front().material, kSoil);
}

TEST(StackAggregation, APyramidHalvesDownToOneStackAndKeepsAnArch) {
  // 8 x 8 stacks of ground to 10 m with an arch 20..24 m over the middle rows.
  std::vector<Column> columns;
  for (int y = 0; y < 8; ++y) {
    for (int x = 0; x < 8; ++x) {
      Column c{{0, 10, kRock}};
      if (y >= 2 && y < 6) c.push_back({20, 24, kRock});
      columns.push_back(c);
    }
  }
  Result<StackTerrain> fine = StackTerrain::fromColumns(8, 8, 2.0, columns);
  ASSERT_TRUE(fine);
  const std::vector<StackTerrain> levels = buildStackPyramid(std::move(fine.value()));
  ASSERT_EQ(levels.size(), 4u);  // 8, 4, 2, 1
  EXPECT_EQ(levels[1].width(), 4);
  EXPECT_DOUBLE_EQ(levels[1].spacingM(), 4.0);
  // Level 1: the arch's rows keep it, the others do not.
  EXPECT_EQ(levels[1].column(1, 1).size(), 2u);
  EXPECT_EQ(levels[1].column(1, 0).size(), 1u);
  // Level 2 mixes one level-1 row with the arch and one without: the arch's segment ties rock
  // and air, with air dominant below it (the gap under the arch) and the sky above: air, the
  // arch is gone at this scale. The ground stays.
  EXPECT_EQ(levels[3].width(), 1);
  ASSERT_GE(levels[3].column(0, 0).size(), 1u);
  EXPECT_EQ(levels[3].column(0, 0)[0], (StackLayer{0, 10, kRock}));
}

TEST(StackFile, RoundTripsAPyramidAndRefusesDamage) {
  std::vector<Column> columns;
  for (int k = 0; k < 5 * 3; ++k) {
    Column c{{0.0f, 3.0f + float(k % 4), kRock}};
    if (k % 3 == 0) c.push_back({8.5f, 9.25f, kSoil});
    columns.push_back(c);
  }
  Result<StackTerrain> fine = StackTerrain::fromColumns(5, 3, 2.0, columns);
  ASSERT_TRUE(fine);
  const std::vector<StackTerrain> levels = buildStackPyramid(std::move(fine.value()));
  const std::filesystem::path dir = test::freshTestDir();
  ASSERT_TRUE(writeStackFile(dir / "t.tstack", levels));
  Result<std::vector<StackTerrain>> back = readStackFile(dir / "t.tstack");
  ASSERT_TRUE(back) << back.error().message;
  ASSERT_EQ(back->size(), levels.size());
  for (std::size_t k = 0; k < levels.size(); ++k) {
    EXPECT_EQ((*back)[k].width(), levels[k].width());
    EXPECT_DOUBLE_EQ((*back)[k].spacingM(), levels[k].spacingM());
    EXPECT_EQ((*back)[k].offsets(), levels[k].offsets());
    EXPECT_EQ((*back)[k].layers(), levels[k].layers());
  }
  Result<StackFileSummary> summary = summariseStackFile(dir / "t.tstack");
  ASSERT_TRUE(summary);
  EXPECT_EQ(summary->levels, 4);  // 5 x 3, 3 x 2, 2 x 1, 1 x 1
  EXPECT_EQ(summary->width, 5);

  // Damage: every byte flipped in turn is caught (checksums, never a crash), truncation too.
  std::ifstream in(dir / "t.tstack", std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (std::size_t at = 0; at < bytes.size(); ++at) {
    std::string damaged = bytes;
    damaged[at] = char(damaged[at] ^ 0x5a);
    std::ofstream(dir / "bad.tstack", std::ios::binary) << damaged;
    EXPECT_FALSE(readStackFile(dir / "bad.tstack")) << "byte " << at;
  }
  std::ofstream(dir / "short.tstack", std::ios::binary) << bytes.substr(0, bytes.size() - 3);
  EXPECT_FALSE(readStackFile(dir / "short.tstack"));
  std::ofstream(dir / "text.tstack") << "not a stack file at all, but long enough to have a header......";
  Result<std::vector<StackTerrain>> text = readStackFile(dir / "text.tstack");
  ASSERT_FALSE(text);
  EXPECT_NE(text.error().message.find("not a Tellus stack file"), std::string::npos);
  EXPECT_FALSE(readStackFile(dir / "missing.tstack"));
}

TEST(StackFile, KeepsTheGeoReferenceOfItsDemAndWritesNoneAsBefore) {
  std::vector<Column> columns(6 * 4, Column{{0.0f, 5.0f, kRock}});
  Result<StackTerrain> fine = StackTerrain::fromColumns(6, 4, 30.0, columns);
  ASSERT_TRUE(fine);
  const std::vector<StackTerrain> levels = buildStackPyramid(std::move(fine.value()));
  const std::filesystem::path dir = test::freshTestDir();
  // Without a georeference: version 1, blocks right after the level table, as before.
  ASSERT_TRUE(writeStackFile(dir / "plain.tstack", levels));
  std::ifstream plainIn(dir / "plain.tstack", std::ios::binary);
  const std::string plain((std::istreambuf_iterator<char>(plainIn)), std::istreambuf_iterator<char>());
  std::uint32_t version = 0;
  std::uint64_t firstBlock = 0;
  std::memcpy(&version, plain.data() + 8, 4);
  std::memcpy(&firstBlock, plain.data() + 64 + 16, 8);
  EXPECT_EQ(version, 1u);
  EXPECT_EQ(firstBlock, 64u + 48u * levels.size());
  Result<GeoReference> none = readStackGeoReference(dir / "plain.tstack");
  ASSERT_TRUE(none) << none.error().message;
  EXPECT_FALSE(hasStackGeoReference(none.value()));

  Result<GeoReference> utm = projectedGeoReference(32652, 350015.0, 4150005.0, 30.0);
  ASSERT_TRUE(utm) << utm.error().message;
  ASSERT_TRUE(writeStackFile(dir / "geo.tstack", levels, utm.value()));
  Result<GeoReference> back = readStackGeoReference(dir / "geo.tstack");
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_EQ(back->crsWkt, utm->crsWkt);
  EXPECT_EQ(back->crsName, utm->crsName);
  EXPECT_EQ(back->geoTransform, utm->geoTransform);
  EXPECT_TRUE(back->hasGeoTransform);
  EXPECT_FALSE(back->isGeographic);
  Result<StackFileSummary> summary = summariseStackFile(dir / "geo.tstack");
  ASSERT_TRUE(summary) << summary.error().message;
  EXPECT_EQ(summary->georef.crsWkt, utm->crsWkt);
  Result<std::vector<StackTerrain>> read = readStackFile(dir / "geo.tstack");
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(read->front().layers(), levels.front().layers());

  // Every byte of the georeferenced file flipped is caught too.
  std::ifstream geoIn(dir / "geo.tstack", std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(geoIn)), std::istreambuf_iterator<char>());
  for (std::size_t at = 0; at < bytes.size(); ++at) {
    std::string damaged = bytes;
    damaged[at] = char(damaged[at] ^ 0x5a);
    std::ofstream(dir / "bad.tstack", std::ios::binary) << damaged;
    EXPECT_FALSE(readStackFile(dir / "bad.tstack")) << "byte " << at;
  }
  // A forged CRS with a valid checksum: named.
  std::string forged = bytes;
  const std::size_t wktAt = 64 + 48 * levels.size() + 60;
  forged.replace(wktAt, 6, "NOTWKT");
  test::resealStackHeader(forged);
  std::ofstream(dir / "forged.tstack", std::ios::binary) << forged;
  Result<GeoReference> refused = readStackGeoReference(dir / "forged.tstack");
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("forged.tstack"), std::string::npos) << refused.error().message;
  EXPECT_NE(refused.error().message.find("georeference"), std::string::npos) << refused.error().message;
}

TEST(StackGenerator, SquareCellsKeepEverySampleWhereItWas) {
  // 0.001 x 0.0005 degrees at the equator: 111 x 55 m, resampled to 55 m cells.
  HeightGrid grid(11, 21);
  grid.spacingXM = 111.3;
  grid.spacingYM = 55.65;
  grid.georef.hasGeoTransform = true;
  grid.georef.isGeographic = true;
  grid.georef.geoTransform = {10.0, 0.001, 0.0, 1.0, 0.0, -0.0005};
  const HeightGrid square = squareCells(grid);
  ASSERT_EQ(square.spacingXM, 55.65);
  ASSERT_GT(square.width, grid.width);
  // Output sample x lies (x * 55.65 / 111.3) input samples east: its centre's longitude.
  const auto& g = square.georef.geoTransform;
  for (const int x : {0, 7, square.width - 1}) {
    const double lon = g[0] + (x + 0.5) * g[1];
    const double expected = 10.0 + (double(x) * 55.65 / 111.3 + 0.5) * 0.001;
    EXPECT_NEAR(lon, expected, 1e-12) << x;
  }
  for (const int y : {0, 5, square.height - 1}) {
    EXPECT_NEAR(g[3] + (y + 0.5) * g[5], 1.0 + (double(y) + 0.5) * -0.0005, 1e-12) << y;
  }
}

TEST(StackSkyHeights, EachValueIsTheHighestTopOfItsColumnsRoundedUp) {
  // 5 x 3 stacks, row 0 north; the middle column of row 1 has a cave under a 20 m roof.
  std::vector<Column> columns(5 * 3, Column{{0.0f, 10.0f, kRock}});
  columns[1 * 5 + 2] = {{0.0f, 4.0f, kRock}, {8.0f, 20.0f, kRock}};
  columns[0 * 5 + 4] = {};  // empty: top 0
  Result<StackTerrain> terrain = StackTerrain::fromColumns(5, 3, 2.0, columns);
  ASSERT_TRUE(terrain);
  const StackSkyHeights sky = stackSkyHeights(terrain.value());
  ASSERT_EQ(sky.factor, 1);
  ASSERT_EQ(sky.width, 5);
  ASSERT_EQ(sky.height, 3);
  const auto top = [&](int i, int j) { return double(sky.values[std::size_t(j * sky.width + i)]) * sky.scaleM; };
  EXPECT_NEAR(top(2, 1), 20.0, 1e-9);  // the roof, not the cave's floor
  EXPECT_GE(top(0, 0), 10.0);           // sample row 0 is the south row
  EXPECT_LT(top(0, 0), 10.0 + sky.scaleM);
  EXPECT_EQ(top(4, 2), 0.0);           // the north-east column, empty
  // Reduced 2 x 2: the highest of each block, the partial blocks at the edges included.
  const StackSkyHeights coarse = stackSkyHeights(terrain.value(), 6);
  ASSERT_EQ(coarse.factor, 2);
  ASSERT_EQ(coarse.width, 3);
  ASSERT_EQ(coarse.height, 2);
  const auto coarseTop = [&](int i, int j) {
    return double(coarse.values[std::size_t(j * coarse.width + i)]) * coarse.scaleM;
  };
  EXPECT_NEAR(coarseTop(1, 0), 20.0, 1e-9);  // sample rows 0-1 (terrain rows 2, 1), columns 2-3
  EXPECT_NEAR(coarseTop(2, 1), 0.0, 1e-9);   // sample row 2 (terrain row 0), column 4
  EXPECT_NEAR(coarseTop(0, 1), 10.0, coarse.scaleM);
}

TEST(StackFile, ForgedFilesWithValidChecksumsAreRefused) {
  std::vector<Column> columns(16 * 16, Column{{0.0f, 12.0f, kRock}});
  Result<StackTerrain> fine = StackTerrain::fromColumns(16, 16, 2.0, columns);
  ASSERT_TRUE(fine);
  std::vector<StackTerrain> levels = buildStackPyramid(std::move(fine.value()));
  const std::filesystem::path dir = test::freshTestDir();
  ASSERT_TRUE(writeStackFile(dir / "t.tstack", levels));
  std::ifstream in(dir / "t.tstack", std::ios::binary);
  const std::string good((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto refused = [&](const std::string& bytes, const std::string& message, const char* what) {
    std::ofstream(dir / "forged.tstack", std::ios::binary) << bytes;
    Result<std::vector<StackTerrain>> read = readStackFile(dir / "forged.tstack");
    ASSERT_FALSE(read) << what;
    EXPECT_NE(read.error().message.find(message), std::string::npos) << what << ": " << read.error().message;
    EXPECT_NE(read.error().message.find("forged.tstack"), std::string::npos) << what;
  };
  // Bytes after the last level.
  refused(good + std::string(4096, 'x'), "4096 bytes follow the last level", "appended");
  // Spacings no terrain has (1e300 crashed the camera paths, 1e-300 drew nothing).
  for (const double spacing : {1e300, 1e-300, -2.0}) {
    std::string bytes = good;
    std::memcpy(bytes.data() + 16, &spacing, 8);
    test::resealStackHeader(bytes);
    refused(bytes, "sample spacing", "spacing");
  }
  // A 17-byte level block that declares 1 GiB of columns (16385 x 16383 stacks, no layer): a
  // zstd frame with its content size and one RLE block. Refused before anything is allocated.
  {
    std::string bytes = good.substr(0, 64 + 48);
    std::uint32_t one = 1, width = 16385, height = 16383;
    std::memcpy(bytes.data() + 12, &one, 4);
    std::memcpy(bytes.data() + 64, &width, 4);
    std::memcpy(bytes.data() + 68, &height, 4);
    const std::uint64_t layers = 0, offset = 64 + 48, frameBytes = 17, declared = std::uint64_t(1) << 30;
    std::memcpy(bytes.data() + 72, &layers, 8);
    std::memcpy(bytes.data() + 80, &offset, 8);
    std::memcpy(bytes.data() + 88, &frameBytes, 8);
    std::string frame = "\x28\xb5\x2f\xfd\xe0";
    frame.append(reinterpret_cast<const char*>(&declared), 8);
    frame += std::string("\x03\x00\x01\x00", 4);  // the last block: 8192 zero bytes (RLE), far short
    ASSERT_EQ(frame.size(), frameBytes);
    bytes += frame;
    test::resealStackHeader(bytes);
    refused(bytes, "more than zstd can expand it to", "declared gigabyte");
  }
  // A level 1 that is not the aggregation of level 0: the file reads (every checksum is its
  // own), verifyStackPyramid names the level.
  std::vector<Column> raised(8 * 8, Column{{0.0f, 112.0f, kRock}});
  Result<StackTerrain> forgedLevel = StackTerrain::fromColumns(8, 8, 4.0, raised);
  ASSERT_TRUE(forgedLevel);
  levels[1] = std::move(forgedLevel.value());
  ASSERT_TRUE(writeStackFile(dir / "level1.tstack", levels));
  Result<std::vector<StackTerrain>> read = readStackFile(dir / "level1.tstack");
  ASSERT_TRUE(read) << read.error().message;
  Status pyramid = verifyStackPyramid(read.value());
  ASSERT_FALSE(pyramid);
  EXPECT_NE(pyramid.error().message.find("level 1 is not the aggregation of level 0"), std::string::npos)
      << pyramid.error().message;
  levels = buildStackPyramid(std::move(levels.front()));
  EXPECT_TRUE(verifyStackPyramid(levels));
}

}  // namespace
}  // namespace tellus
