// Output and input file hygiene: atomic writes, refused destinations, swept temporaries,
// scratch folders, non-blocking input checks and the memory budget.
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "support/test_support.hpp"
#include "tellus/core/atomic_output.hpp"
#include "tellus/core/input_file.hpp"
#include "tellus/core/memory_budget.hpp"
#include "tellus/core/rgb_image.hpp"
#include "tellus/core/scratch_folder.hpp"

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

TEST(AtomicOutput, RefusesDevicesAndProtectedInputsWhateverTheirName) {
  const fs::path dir = test::freshTestDir();
  const fs::path null = dir / "null";  // the test's own, so a regression harms nothing else
  if (::mknod(null.c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0) {
    Status device = writeTextFileAtomically(null, "text");
    ASSERT_FALSE(device);
    EXPECT_NE(device.error().message.find("character device"), std::string::npos);
    struct stat info {};
    ASSERT_EQ(::stat(null.c_str(), &info), 0);
    EXPECT_TRUE(S_ISCHR(info.st_mode));
    fs::remove(null);
  }
  std::ofstream(dir / "input.tif") << "heights";
  fs::create_hard_link(dir / "input.tif", dir / "alias.tif");
  protectInputFiles({dir / "input.tif"});
  Status input = writeTextFileAtomically(dir / "alias.tif", "clobbered");
  clearProtectedInputFiles();
  ASSERT_FALSE(input);
  EXPECT_NE(input.error().message.find("it is the input"), std::string::npos);
  std::ifstream in(dir / "input.tif");
  std::string content;
  in >> content;
  EXPECT_EQ(content, "heights");
  EXPECT_TRUE(writeTextFileAtomically(dir / "alias.tif", "now allowed"));
}

TEST(AtomicOutput, SweepsTemporariesOfDeadProcessesOnly) {
  const fs::path dir = test::freshTestDir();
  const pid_t dead = ::fork();
  if (dead == 0) ::_exit(0);
  ::waitpid(dead, nullptr, 0);
  const fs::path stale = dir / fmt::format(".out.json.tellus-partial-{}-4", dead);
  const fs::path live = dir / fmt::format(".out.json.tellus-partial-{}-9", ::getpid());
  const fs::path staleScratch = dir / fmt::format(".tellus-scratch-{}-1", dead);
  const fs::path staleOther = dir / fmt::format(".other.tif.tellus-partial-{}-2", dead);
  const fs::path unrelated = dir / fmt::format(".cache-{}", dead);
  std::ofstream(stale) << "x";
  std::ofstream(staleOther) << "x";
  std::ofstream(unrelated) << "x";
  std::ofstream(live) << "x";
  fs::create_directories(staleScratch / "inner");
  ASSERT_TRUE(writeTextFileAtomically(dir / "out.json", "{}"));
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_FALSE(fs::exists(staleOther));  // any output's, not only this one's
  EXPECT_TRUE(fs::exists(unrelated));    // not a name Tellus gives
  EXPECT_FALSE(fs::exists(staleScratch));
  EXPECT_TRUE(fs::exists(live));
}

TEST(ScratchFolder, IsPrivateAndRemovedWithItsContent) {
  const fs::path dir = test::freshTestDir();
  fs::path inside;
  {
    Result<ScratchFolder> scratch = ScratchFolder::create(dir);
    ASSERT_TRUE(scratch) << scratch.error().message;
    inside = scratch->path() / "work.tif";
    std::ofstream(inside) << "gdal work file";
    EXPECT_EQ(scratch->path().parent_path(), dir);
    EXPECT_TRUE(scratch->path().filename().string().starts_with(".tellus-scratch-"));
  }
  EXPECT_FALSE(fs::exists(inside));
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST(InputFile, RefusesAFifoWithoutBlocking) {
  const fs::path dir = test::freshTestDir();
  const fs::path fifo = dir / "fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  Status checked = checkRegularInput(fifo);
  ASSERT_FALSE(checked);
  EXPECT_NE(checked.error().message.find("it is a FIFO"), std::string::npos);
  Result<std::string> read = readSmallInputFile(fifo, 1024);  // would block without O_NONBLOCK
  ASSERT_FALSE(read);
  EXPECT_NE(read.error().message.find("it is a FIFO"), std::string::npos);
  EXPECT_FALSE(checkRegularInput(dir));
  EXPECT_FALSE(checkRegularInput(dir / "missing"));
  std::ofstream(dir / "big.json") << std::string(2000, ' ');
  Result<std::string> big = readSmallInputFile(dir / "big.json", 1000);
  ASSERT_FALSE(big);
  EXPECT_NE(big.error().message.find("2000 bytes"), std::string::npos);
  EXPECT_TRUE(checkRegularInput("/vsimem/anything.tif"));  // GDAL's own streams
}

TEST(MemoryBudget, RefusesWithBothFiguresAndTheWayOut) {
  EXPECT_GT(availableMemoryBytes(), 0u);
  Status absurd = checkMemoryFor("loading 'x'", 1e30, "build a tile store");
  ASSERT_FALSE(absurd);
  EXPECT_NE(absurd.error().message.find("loading 'x' needs about"), std::string::npos);
  EXPECT_NE(absurd.error().message.find("available; build a tile store"), std::string::npos);
  EXPECT_TRUE(checkMemoryFor("a little", 1024.0, ""));
  EXPECT_EQ(formatByteCount(1536.0), "1.5 KiB");
  EXPECT_EQ(formatByteCount(40.0 * (1 << 30)), "40.00 GiB");
}

}  // namespace
}  // namespace tellus
