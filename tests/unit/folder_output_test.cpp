// Output folders (tellus/core/folder_output.hpp): written whole or not at all, swapped in with
// one rename, and never replacing what Tellus did not write, what holds an input, or the
// current folder.
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "support/test_support.hpp"
#include "tellus/core/atomic_output.hpp"
#include "tellus/core/folder_output.hpp"

namespace tellus {
namespace {
namespace fs = std::filesystem;

// A folder kind of files "N.dat" and folders "N" (digits), like a tile set.
FolderOutputKind numberedKind() {
  FolderOutputKind kind;
  kind.description = "a numbered set";
  kind.markerName = ".tellus-numbered";
  kind.markerContent = "{}\n";
  kind.ownEntry = [](const fs::path& relative) {
    const std::string name = relative.filename().string();
    return !name.empty() && (std::isdigit(static_cast<unsigned char>(name[0])) != 0);
  };
  return kind;
}

// Writes a complete set with `content` in 1.dat into `folder` through FolderOutput.
Status writeSet(const fs::path& folder, const std::string& content) {
  Result<FolderOutput> output = FolderOutput::begin(folder, numberedKind());
  if (!output) return output.error();
  std::ofstream(output->temporary() / "1.dat") << content;
  return output->commit();
}

std::string read(const fs::path& file) {
  std::ifstream in(file);
  std::string text;
  in >> text;
  return text;
}

pid_t deadPid() {
  const pid_t pid = ::fork();
  if (pid == 0) ::_exit(0);
  ::waitpid(pid, nullptr, 0);
  return pid;
}

class FolderOutputTest : public ::testing::Test {
 protected:
  void TearDown() override { clearProtectedInputFiles(); }
};

TEST_F(FolderOutputTest, WritesANewFolderAndReplacesItsOwnWhole) {
  const fs::path dir = test::freshTestDir();
  ASSERT_TRUE(writeSet(dir / "set", "first"));
  EXPECT_EQ(read(dir / "set" / "1.dat"), "first");
  EXPECT_TRUE(fs::exists(dir / "set" / ".tellus-numbered"));
  ASSERT_TRUE(writeSet(dir / "set", "second"));
  EXPECT_EQ(read(dir / "set" / "1.dat"), "second");
  // Nothing beside it: the temporary and the old set are gone.
  int entries = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++entries;
  EXPECT_EQ(entries, 1);
}

TEST_F(FolderOutputTest, AFolderNeverCommittedLeavesTheOldOneAndNoTemporary) {
  const fs::path dir = test::freshTestDir();
  ASSERT_TRUE(writeSet(dir / "set", "old"));
  {
    Result<FolderOutput> output = FolderOutput::begin(dir / "set", numberedKind());
    ASSERT_TRUE(output) << output.error().message;
    std::ofstream(output->temporary() / "1.dat") << "half";
  }  // a failed export: destroyed without commit()
  EXPECT_EQ(read(dir / "set" / "1.dat"), "old");
  int entries = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++entries;
  EXPECT_EQ(entries, 1);
}

TEST_F(FolderOutputTest, RefusesFoldersTellusDidNotWrite) {
  const fs::path dir = test::freshTestDir();
  // Files but no marker.
  fs::create_directories(dir / "plain");
  std::ofstream(dir / "plain" / "1.dat") << "user data";
  Status plain = checkFolderOutput(dir / "plain", numberedKind());
  ASSERT_FALSE(plain);
  EXPECT_NE(plain.error().message.find("no '.tellus-numbered' marker"), std::string::npos)
      << plain.error().message;
  // A marker, and something else beside the set's own entries (named in the message).
  ASSERT_TRUE(writeSet(dir / "mixed", "set"));
  fs::create_directories(dir / "mixed" / "docs");
  std::ofstream(dir / "mixed" / "docs" / "notes.txt") << "keep me";
  Status mixed = checkFolderOutput(dir / "mixed", numberedKind());
  ASSERT_FALSE(mixed);
  EXPECT_NE(mixed.error().message.find("'docs'"), std::string::npos) << mixed.error().message;
  EXPECT_FALSE(writeSet(dir / "mixed", "new"));
  EXPECT_EQ(read(dir / "mixed" / "docs" / "notes.txt"), "keep");
  // A symbolic link inside counts as foreign (never followed, never deleted through).
  ASSERT_TRUE(writeSet(dir / "linked", "set"));
  fs::create_directory_symlink(dir / "plain", dir / "linked" / "2");
  EXPECT_FALSE(checkFolderOutput(dir / "linked", numberedKind()));
  // An empty folder is fine.
  fs::create_directories(dir / "empty");
  EXPECT_TRUE(writeSet(dir / "empty", "new"));
}

TEST_F(FolderOutputTest, RefusesAFolderHoldingAnInput) {
  const fs::path dir = test::freshTestDir();
  ASSERT_TRUE(writeSet(dir / "set", "old"));
  protectInputFiles({dir / "set" / "1.dat"});
  Status holds = checkFolderOutput(dir / "set", numberedKind());
  ASSERT_FALSE(holds);
  EXPECT_NE(holds.error().message.find("holds the input"), std::string::npos) << holds.error().message;
  EXPECT_FALSE(writeSet(dir / "set", "new"));
  EXPECT_EQ(read(dir / "set" / "1.dat"), "old");
}

TEST_F(FolderOutputTest, RefusesTheCurrentFolderItsParentsAndNonFolders) {
  const fs::path dir = test::freshTestDir();
  const fs::path before = fs::current_path();
  fs::create_directories(dir / "work");
  fs::current_path(dir / "work");
  EXPECT_FALSE(checkFolderOutput(".", numberedKind()));
  EXPECT_FALSE(checkFolderOutput("..", numberedKind()));
  EXPECT_FALSE(checkFolderOutput(dir, numberedKind()));
  fs::current_path(before);
  EXPECT_FALSE(checkFolderOutput("/", numberedKind()));
  std::ofstream(dir / "file") << "x";
  Status file = checkFolderOutput(dir / "file", numberedKind());
  ASSERT_FALSE(file);
  EXPECT_NE(file.error().message.find("it is a file, not a folder"), std::string::npos);
  Status device = checkFolderOutput("/dev/null", numberedKind());
  ASSERT_FALSE(device);
  EXPECT_NE(device.error().message.find("character device"), std::string::npos);
}

TEST_F(FolderOutputTest, SweepsTheTemporariesOfDeadProcessesAndPutsASetAsideFolderBack) {
  const fs::path dir = test::freshTestDir();
  const pid_t dead = deadPid();
  // A killed writer's temporary: removed by the next write there.
  const fs::path stale = dir / fmt::format(".set.tellus-partial-{}-0", dead);
  fs::create_directories(stale / "7");
  // A killed replacement between its two renames (file systems without RENAME_EXCHANGE): the
  // old folder aside and nothing in its place. It comes back.
  const fs::path aside = dir / fmt::format(".other.tellus-previous-{}-1", dead);
  fs::create_directories(aside);
  std::ofstream(aside / "1.dat") << "precious";
  ASSERT_TRUE(writeSet(dir / "set", "new"));
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_FALSE(fs::exists(aside));
  EXPECT_EQ(read(dir / "other" / "1.dat"), "precious");
}

}  // namespace
}  // namespace tellus
