// Material stacks (seed 003) end to end: a generated DEM becomes a .tstack with caves, overhangs
// and arches, tellus info describes it, tellus verify passes it and fails a damaged copy, and
// wrong uses say what is wrong.
#include <fstream>

#include <gtest/gtest.h>

#include "cli/run_tellus.hpp"
#include "support/test_support.hpp"

namespace tellus {
namespace {
namespace fs = std::filesystem;

TEST(StacksCli, BuildInfoVerifyAndRefusals) {
  const fs::path dir = test::freshTestDir();
  const fs::path dem = dir / "hills.tif", stacks = dir / "hills.tstack";
  ASSERT_EQ(runTellus(fmt::format("generate --size 129 --spacing 3 --relief 120 -o {}", quoted(dem))).exitCode, 0);
  const RunResult built = runTellus(fmt::format("stacks build {} -o {} --seed 3", quoted(dem), quoted(stacks)));
  ASSERT_EQ(built.exitCode, 0) << built.output;
  EXPECT_NE(built.output.find("129 x 129 stacks at 3 m, 9 levels"), std::string::npos) << built.output;
  const RunResult info = runTellus(fmt::format("info {}", quoted(stacks)));
  ASSERT_EQ(info.exitCode, 0) << info.output;
  EXPECT_NE(info.output.find("material stacks, 129 x 129 stacks"), std::string::npos) << info.output;
  EXPECT_NE(info.output.find("level 8: 1 x 1 stacks"), std::string::npos) << info.output;
  const RunResult verified = runTellus(fmt::format("verify {}", quoted(stacks)));
  ASSERT_EQ(verified.exitCode, 0) << verified.output;
  EXPECT_NE(verified.output.find("all 9 levels good"), std::string::npos);
  // The same seed, the same file; without features, three layers at most a stack.
  const fs::path again = dir / "again.tstack", plain = dir / "plain.tstack";
  ASSERT_EQ(runTellus(fmt::format("stacks build {} -o {} --seed 3", quoted(dem), quoted(again))).exitCode, 0);
  std::ifstream a(stacks, std::ios::binary), b(again, std::ios::binary);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(a), {}), std::string(std::istreambuf_iterator<char>(b), {}));
  ASSERT_EQ(runTellus(fmt::format("stacks build {} -o {} --features none", quoted(dem), quoted(plain))).exitCode, 0);
  const RunResult plainInfo = runTellus(fmt::format("info {}", quoted(plain)));
  EXPECT_NE(plainInfo.output.find("up to"), std::string::npos);

  // A damaged copy fails verify with the level named.
  std::string bytes;
  {
    std::ifstream in(stacks, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  bytes[bytes.size() / 2] = char(bytes[bytes.size() / 2] ^ 0x40);
  std::ofstream(dir / "bad.tstack", std::ios::binary) << bytes;
  const RunResult bad = runTellus(fmt::format("verify {}", quoted(dir / "bad.tstack")));
  EXPECT_NE(bad.exitCode, 0);
  EXPECT_NE(bad.output.find("corrupt"), std::string::npos) << bad.output;

  const std::vector<std::pair<std::string, std::string>> cases = {
      {fmt::format("stacks build {} -o {}", quoted(dem), quoted(dir / "x.tif")), "must end in .tstack"},
      {fmt::format("stacks build {} -o {}", quoted(dir / "missing.tif"), quoted(dir / "x.tstack")), "missing.tif"},
      {fmt::format("stacks build {} -o {} --features tunnels", quoted(dem), quoted(dir / "x.tstack")), "tunnels"},
      {fmt::format("verify {}", quoted(dem)), "hills.tif"},
      {"stacks", "subcommand"},
  };
  for (const auto& [arguments, expected] : cases) {
    const RunResult r = runTellus(arguments);
    EXPECT_NE(r.exitCode, 0) << arguments;
    EXPECT_NE(r.output.find(expected), std::string::npos) << arguments << "\n" << r.output;
  }
  EXPECT_FALSE(fs::exists(dir / "x.tstack"));
}

}  // namespace
}  // namespace tellus
