// DemSource: streaming reads equal the whole-grid loader, and void filling on disk (the path
// large inputs take) gives the same heights as in memory, leaving no scratch files behind.
#include <gtest/gtest.h>

#include "support/test_support.hpp"
#include "tellus/dem/dem_loader.hpp"
#include "tellus/dem/dem_source.hpp"

namespace tellus {
namespace {
namespace fs = std::filesystem;

std::vector<float> readAll(DemSource& source, int rowsPerRead) {
  const DemSourceInfo& info = source.info();
  std::vector<float> all(std::size_t(info.width) * std::size_t(info.height));
  for (int row = 0; row < info.height; row += rowsPerRead) {
    const int count = std::min(rowsPerRead, info.height - row);
    std::span<float> rows(all.data() + std::size_t(row) * std::size_t(info.width),
                          std::size_t(count) * std::size_t(info.width));
    EXPECT_TRUE(source.readRows(row, count, rows));
  }
  return all;
}

TEST(DemSource, FillsVoidsOnDiskLikeInMemory) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path hgt = data / "srtm3-hgt-east-asia/N37E127.hgt";  // 5 voids
  Result<HeightGrid> loaded = loadDem({hgt});
  ASSERT_TRUE(loaded);
  const fs::path scratch = test::freshTestDir();
  Result<std::unique_ptr<DemSource>> source = DemSource::open({hgt});
  ASSERT_TRUE(source);
  EXPECT_EQ(source.value()->info().heightStepM, 1.0);
  Result<std::size_t> voids = source.value()->fillVoids(scratch, /*inMemorySamples=*/0);
  ASSERT_TRUE(voids) << voids.error().message;
  EXPECT_EQ(voids.value(), loaded->filledVoidCount);
  EXPECT_FALSE(fs::is_empty(scratch)) << "the scratch copy should be on disk";
  const std::vector<float> streamed = readAll(*source.value(), 97);
  ASSERT_EQ(streamed.size(), loaded->heights.size());
  for (std::size_t i = 0; i < streamed.size(); ++i) {
    ASSERT_NEAR(streamed[i], loaded->heights[i], 1e-3f) << "sample " << i;
  }
  EXPECT_FALSE(source.value()->readRows(1200, 2, std::span<float>()));  // outside the grid
  source.value().reset();
  EXPECT_TRUE(fs::is_empty(scratch)) << "scratch files left behind";
}

}  // namespace
}  // namespace tellus
