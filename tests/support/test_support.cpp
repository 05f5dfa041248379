#include "support/test_support.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <mutex>
#include <vector>

#include <unistd.h>

#include <fmt/format.h>

namespace tellus::test {
namespace fs = std::filesystem;

std::optional<fs::path> sharedDataDir() {
  const char* env = std::getenv("TELLUS_DATA_DIR");
  const fs::path dir = env ? fs::path(env) : fs::path(TELLUS_SHARED_DATA_DIR);
  std::error_code ec;
  if (fs::is_directory(dir / "srtm3-hgt-east-asia", ec)) return dir;
  return std::nullopt;
}

std::vector<fs::path> koreaMosaicTiles(const fs::path& dataDir) {
  std::vector<fs::path> tiles;
  for (int lat = 34; lat <= 37; ++lat) {
    for (int lon = 126; lon <= 129; ++lon) {
      tiles.push_back(dataDir / "srtm3-hgt-east-asia" / fmt::format("N{}E{}.hgt", lat, lon));
    }
  }
  return tiles;
}

fs::path testOutputDir() {
  const fs::path dir(TELLUS_TEST_OUTPUT_DIR);
  fs::create_directories(dir);
  return dir;
}

std::string readFileBytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

fs::path freshTestDir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = fmt::format("{}.{}", info->test_suite_name(), info->name());
  for (char& c : name) {
    if (c == '/') c = '_';
  }
  const fs::path dir = testOutputDir() / "tmp" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

namespace {
// The fixture folders this process made, removed at its exit (after the fixtures' own statics,
// which were made later and so are destroyed first).
struct ProcessFixtureDirs {
  std::mutex mutex;
  std::vector<fs::path> dirs;
  ~ProcessFixtureDirs() {
    for (const fs::path& dir : dirs) {
      std::error_code ignored;
      fs::remove_all(dir, ignored);
    }
  }
};
ProcessFixtureDirs& processFixtureDirs() {
  static ProcessFixtureDirs registry;
  return registry;
}
}  // namespace

fs::path processFixtureDir(const std::string& name) {
  ProcessFixtureDirs& registry = processFixtureDirs();
  const fs::path dir = testOutputDir() / "fixtures" / fmt::format("{}-{}", name, ::getpid());
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::lock_guard lock(registry.mutex);
  registry.dirs.push_back(dir);
  return dir;
}

ForegroundStats foregroundStats(const RgbImage& image, const unsigned char background[3],
                                int tolerance) {
  ForegroundStats stats;
  stats.minX = image.width;
  stats.minY = image.height;
  double count = 0.0, sumX = 0.0, sumY = 0.0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const std::uint8_t* p = image.at(x, y);
      bool foreground = false;
      for (int c = 0; c < 3; ++c)
        foreground |= std::abs(int(p[c]) - int(background[c])) > tolerance;
      if (!foreground) continue;
      count += 1.0;
      sumX += x;
      sumY += y;
      stats.minX = std::min(stats.minX, x);
      stats.maxX = std::max(stats.maxX, x);
      stats.minY = std::min(stats.minY, y);
      stats.maxY = std::max(stats.maxY, y);
    }
  }
  stats.fraction = count / (double(image.width) * double(image.height));
  if (count > 0) {
    stats.centroidX = sumX / count;
    stats.centroidY = sumY / count;
  }
  return stats;
}

double luminanceStdDev(const RgbImage& image) {
  double sum = 0.0, sumSq = 0.0;
  const double n = double(image.width) * double(image.height);
  for (size_t i = 0; i < image.pixels.size(); i += 3) {
    const double l =
        0.2126 * image.pixels[i] + 0.7152 * image.pixels[i + 1] + 0.0722 * image.pixels[i + 2];
    sum += l;
    sumSq += l * l;
  }
  const double mean = sum / n;
  return std::sqrt(std::max(0.0, sumSq / n - mean * mean));
}

double meanDifference(const RgbImage& a, const RgbImage& b, int x0, int x1) {
  if (x1 < 0) x1 = a.width;
  double sum = 0.0;
  std::size_t count = 0;
  for (int y = 0; y < a.height; ++y) {
    for (int x = x0; x < x1; ++x) {
      for (int c = 0; c < 3; ++c) sum += std::abs(int(a.at(x, y)[c]) - int(b.at(x, y)[c]));
      count += 3;
    }
  }
  return count ? sum / double(count) : 0.0;
}

std::map<std::string, std::string> probeVideo(const std::filesystem::path& file) {
  std::string quotedFile = "'";
  for (char c : file.string()) quotedFile += c == '\'' ? std::string("'\\''") : std::string(1, c);
  quotedFile += "'";
  const std::string command =
      "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
      "stream=codec_name,width,height,pix_fmt,nb_read_frames:format=duration,format_name -of default=nw=1 " +
      quotedFile + " 2>&1";
  std::map<std::string, std::string> out;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return {{"error", "cannot run ffprobe"}};
  char line[512];
  while (fgets(line, sizeof(line), pipe)) {
    std::string text(line);
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
    const auto eq = text.find('=');
    if (eq != std::string::npos) out[text.substr(0, eq)] = text.substr(eq + 1);
    else if (!text.empty()) out["error"] += text;
  }
  if (pclose(pipe) != 0) out["error"] += " (ffprobe failed)";
  return out;
}

}  // namespace tellus::test
