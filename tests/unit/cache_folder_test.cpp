// derivedCacheFolder(): beside a local input, in the user's cache for a URL (never a folder
// named after the URL under the current directory, as the spiral's textures once were).
#include <cstdlib>

#include <gtest/gtest.h>

#include "support/test_support.hpp"
#include "tellus/core/cache_folder.hpp"

namespace tellus {
namespace {
namespace fs = std::filesystem;

TEST(CacheFolder, BesideALocalInputAndInTheUserCacheForAUrl) {
  const fs::path dir = test::freshTestDir();
  EXPECT_EQ(derivedCacheFolder((dir / "earth.tstore").string(), ".spiral-textures", "spiral-textures"),
            fs::absolute(dir / "earth.tstore.spiral-textures"));
  const char* before = std::getenv("XDG_CACHE_HOME");
  const std::string saved = before ? before : "";
  setenv("XDG_CACHE_HOME", (dir / "cache").c_str(), 1);
  const fs::path forUrl =
      derivedCacheFolder("http://127.0.0.1:8080/planet.tstore", ".spiral-textures", "spiral-textures");
  if (before) setenv("XDG_CACHE_HOME", saved.c_str(), 1); else unsetenv("XDG_CACHE_HOME");
  EXPECT_EQ(forUrl.parent_path(), dir / "cache" / "tellus" / "spiral-textures");
  EXPECT_EQ(forUrl.filename().string().find_first_of(":/"), std::string::npos) << forUrl;
  EXPECT_NE(forUrl.filename().string().find("planet.tstore"), std::string::npos) << forUrl;
}

}  // namespace
}  // namespace tellus
