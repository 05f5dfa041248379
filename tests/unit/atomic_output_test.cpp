#include <fstream>

#include <gtest/gtest.h>

#include "support/test_support.hpp"
#include "tellus/core/atomic_output.hpp"
#include "tellus/core/rgb_image.hpp"

namespace tellus {
namespace {
namespace fs = std::filesystem;

size_t filesIn(const fs::path& dir) {
  return size_t(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

TEST(AtomicOutput, AppearsOnlyWhenTheWriteSucceeds) {
  const fs::path dir = test::freshTestDir();
  Status ok = writeFileAtomically(dir / "good.txt", [](const fs::path& temp) -> Status {
    std::ofstream(temp) << "hello";
    return {};
  });
  ASSERT_TRUE(ok) << ok.error().message;
  EXPECT_TRUE(fs::exists(dir / "good.txt"));
  Status failed = writeFileAtomically(dir / "bad.txt", [](const fs::path& temp) -> Status {
    std::ofstream(temp) << "half of it";
    return makeError("writer failed half way");
  });
  EXPECT_FALSE(failed);
  EXPECT_FALSE(fs::exists(dir / "bad.txt"));
  EXPECT_EQ(filesIn(dir), 1u);  // no temporary left behind
}

TEST(AtomicOutput, ExplainsWhyAPathCannotBeWritten) {
  const fs::path dir = test::freshTestDir();
  Status missing = checkOutputWritable(dir / "no-such-folder" / "x.png");
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("does not exist"), std::string::npos);
  Status folder = checkOutputWritable(dir);
  ASSERT_FALSE(folder);
  EXPECT_NE(folder.error().message.find("is a folder"), std::string::npos);
  EXPECT_TRUE(checkOutputWritable(dir / "fine.png"));
}

TEST(AtomicOutput, PngRoundTrip) {
  const fs::path file = test::freshTestDir() / "image.png";
  RgbImage image(7, 5);
  for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = std::uint8_t(i * 7);
  ASSERT_TRUE(writePng(image, file));
  Result<RgbImage> back = readPng(file);
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_EQ(back->width, 7);
  EXPECT_EQ(back->height, 5);
  EXPECT_EQ(back->pixels, image.pixels);
  EXPECT_FALSE(readPng(file.parent_path() / "missing.png"));
}

}  // namespace
}  // namespace tellus
