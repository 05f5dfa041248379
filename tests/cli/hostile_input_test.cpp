// Hostile input, class by class, end to end through the tellus binary: absurd sizes, non-finite
// and out-of-range numbers, degenerate georeferencing, non-regular files, outputs that are
// inputs, shell metacharacters, failing writes, litter, unhelpful messages and checksummed
// nonsense in stores. Every case must end with a message, an exit status from 1 to 127 (never a
// signal, never a hang: each command runs under `timeout`) and no output or temporary file.
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <fstream>
#include <iterator>
#include <regex>
#include <thread>

#include <fmt/format.h>
#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogr_spatialref.h>

#include "cli/hostile_support.hpp"
#include "support/store_surgery.hpp"
#include "support/test_support.hpp"
#include "tellus/tiles/store_format.hpp"

namespace tellus {
namespace {
namespace fs = std::filesystem;

// Class 1: a command estimates what it will allocate and refuses with the figure and the way
// out, instead of dying of std::bad_alloc.
TEST(Hostile, AbsurdSizesAreRefusedWithTheFigureAndTheWayOut) {
  const fs::path dir = test::freshTestDir();
  const fs::path huge = dir / "huge.tif";
  writeSparseHugeGeoTiff(huge);
  EXPECT_LT(fs::file_size(huge), 4u << 20) << "sparse file expected";
  // A VRT claiming 2^31 - 1 samples a side over it.
  const fs::path vrt = dir / "huge.vrt";
  writeText(vrt, fmt::format(R"(<VRTDataset rasterXSize="2147483647" rasterYSize="2147483647">
  <VRTRasterBand dataType="Int16" band="1"><SimpleSource>
    <SourceFilename relativeToVRT="1">huge.tif</SourceFilename><SourceBand>1</SourceBand>
  </SimpleSource></VRTRasterBand></VRTDataset>)"));

  // info streams statistics over a sample of rows, in constant memory.
  const RunResult info = runBounded("info " + quoted(huge));
  ASSERT_EQ(info.exitCode, 0) << info.output;
  EXPECT_NE(info.output.find("100000 x 100000 samples"), std::string::npos) << info.output;
  EXPECT_NE(info.output.find("estimated from 1 row in"), std::string::npos) << info.output;

  const fs::path out = dir / "out.png";
  for (const std::string& command :
       {fmt::format("render {} -o {}", quoted(huge), quoted(out)),
        fmt::format("bench {} --frames 1", quoted(huge)),
        fmt::format("view {} --frames 1", quoted(huge))}) {
    const RunResult result = runBounded(command);
    expectRefused(result, "(100000 x 100000 samples) needs about", command);
    EXPECT_NE(result.output.find("GiB of memory, more than the"), std::string::npos);
    EXPECT_NE(result.output.find("tellus build"), std::string::npos) << result.output;
  }
  for (const std::string& command : {fmt::format("info {}", quoted(vrt)),
                                     fmt::format("render {} -o {}", quoted(vrt), quoted(out))}) {
    expectRefused(runBounded(command), "Tellus reads rasters of up to 16777217 samples a side",
                  command);
  }
  // A 251-byte TIFF found by the DEM fuzzer: 21505 pixel-interleaved bands of 63471 samples, so
  // GDAL would allocate and clear 5 GiB per block before finding the data missing (22 s, 5 GiB
  // of memory). Refused at once. (The fuzzer's inputs start with two bytes of its own.)
  const std::string found =
      contentOf(fs::path(TELLUS_FUZZ_CORPUS_DIR) / "fuzz_dem_load/pixel-interleaved-5gib-blocks");
  ASSERT_GT(found.size(), 2u);
  writeText(dir / "blocks.tif", found.substr(2));
  const RunResult blocks = runBounded("info " + quoted(dir / "blocks.tif"), 10);
  expectRefused(blocks, "blocks of 63471 x 1 samples in 21505 bands (5.08 GiB each", "5 GiB blocks");
  fs::remove(dir / "blocks.tif");
  // generate's own range allows 65537, which needs 32 GiB: refused with the size that fits.
  const RunResult generate =
      runBounded(fmt::format("generate -o {} --size 65537", quoted(dir / "g.tif")));
  expectRefused(generate, "generating a 65537 x 65537 terrain needs about 32.00 GiB", "generate");
  EXPECT_NE(generate.output.find("use a smaller --size (about"), std::string::npos);
  EXPECT_EQ(filesIn(dir), (std::vector<std::string>{"huge.tif", "huge.vrt"}));
}

// The numeric options every subcommand lists in its --help ("--name INT..." / "FLOAT" /
// "UINT"), so that an option added later is covered without touching this test.
std::vector<std::pair<std::string, std::string>> numericOptions() {
  std::vector<std::pair<std::string, std::string>> options;
  const std::regex line(R"(^\s+(?:-\w,)?(--[a-z-]+) (?:INT|UINT|FLOAT))");
  for (const char* sub :
       {"info", "render", "generate", "demo", "build", "verify", "export", "bench",
        "bench codecs", "view"}) {
    const RunResult help = runTellus(fmt::format("{} --help", sub));
    std::istringstream lines(help.output);
    for (std::string text; std::getline(lines, text);) {
      std::smatch match;
      if (std::regex_search(text, match, line)) options.emplace_back(sub, match[1]);
    }
  }
  return options;
}

// Class 2: every number of every option is finite and in range, and the range reads well.
TEST(Hostile, EveryNumericOptionRefusesNonFiniteAndOutOfRangeValues) {
  const fs::path dir = test::freshTestDir();
  const auto options = numericOptions();
  ASSERT_GE(options.size(), 40u) << "the --help parsing found too few numeric options";
  const std::regex longNumber(R"(\d{25})");
  struct Case {
    std::string option, command;
    RunResult result;
  };
  std::vector<Case> runs;
  for (const auto& [sub, option] : options) {
    for (const char* value : {"nan", "inf", "-inf", "1e308", "-1e308"}) {
      runs.push_back({option, fmt::format("{} {} {} -o {}", sub, option, value, quoted(dir / "never")), {}});
    }
  }
  // Hundreds of short processes: run them two at a time (the CI machine's cores), check after.
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (std::size_t i = next++; i < runs.size(); i = next++) runs[i].result = runBounded(runs[i].command, 20);
  };
  std::thread helper(worker);
  worker();
  helper.join();
  for (const Case& run : runs) {
    expectRefused(run.result, run.option, run.command);
    EXPECT_FALSE(std::regex_search(run.result.output, longNumber))
        << run.command << ": the range should read well:\n"
        << run.result.output;
  }
  // Specific wraps and silent defaults the issue found.
  writeSmallGeoTiff(dir / "x.tif", kGoodGeoTransform);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"generate -o {dir}/g.tif --seed -1", "--seed: -1 is outside 0 to 4294967295"},
      {"generate -o {dir}/g.tif --relief nan", "not a finite number"},
      {"generate -o {dir}/g.tif --spacing nan", "not a finite number"},
      {"build x.tif -o {dir}/x.tstore --max-error -1", "--max-error: -1 is outside 0 to 10000"},
      {"build x.tif -o {dir}/x.tstore --max-error nan", "not a finite number"},
      {"build x.tif -o {dir}/x.tstore --quantum 0", "--quantum: 0 is outside 1e-06 to 100"},
      {"build x.tif -o {dir}/x.tstore --quantum 1e308", "--quantum: 1e308 is outside"},
      {"render x.tif -o {dir}/x.png --exaggeration nan", "not a finite number"},
      {"render x.tif -o {dir}/x.png --spacing 1e300", "--spacing: 1e300 is outside 1e-06 to"},
      {"render x.tif -o {dir}/x.png --camera 1e308,0,100,0,-10,45", "x 1e+308 m is not within"},
      {"render x.tif -o {dir}/x.png --level 1.5", "not a whole number"},
  };
  for (auto [command, message] : cases) {
    for (std::size_t at = command.find("{dir}"); at != std::string::npos;
         at = command.find("{dir}")) {
      command.replace(at, 5, dir.string());
    }
    expectRefused(runShell(fmt::format("cd {} && timeout -s KILL 20 '{}' {}", quoted(dir),
                                       TELLUS_EXECUTABLE, command)),
                  message, command);
  }
  // Keyframe files: numbers out of any sensible range, before anything is loaded.
  const fs::path keys = dir / "keys.json";
  writeText(keys, R"({"keyframes": [
    {"time": 0, "position": [1e308, 0, 100], "yaw": 0, "pitch": -10},
    {"time": 1, "position": [10, 0, 100], "yaw": 0, "pitch": -10}]})");
  const RunResult view =
      runBounded(fmt::format("view {} --path {} --frames 2", quoted(dir / "x.tif"), quoted(keys)));
  expectRefused(view, "keyframe 0: x 1e+308 m is not within", "view --path keys.json");
  EXPECT_EQ(filesIn(dir), (std::vector<std::string>{"keys.json", "x.tif"}));
}

// Class 3: a georeferencing without meaning is refused when the DEM is loaded, by every command.
TEST(Hostile, DegenerateGeoreferencingIsRefusedAtLoad) {
  const fs::path dir = test::freshTestDir();
  const double nan = std::nan("");
  const std::vector<std::pair<std::string, std::array<double, 6>>> rasters = {
      {"zero-pixel.tif", {127.0, 0.0, 0.0, 37.5, 0.0, 0.0}},
      {"nan-pixel.tif", {127.0, nan, 0.0, 37.5, 0.0, -0.001}},
      {"latitude-1000.tif", {127.0, 0.001, 0.0, 1000.0, 0.0, -0.001}},
  };
  for (const auto& [name, gt] : rasters) writeSmallGeoTiff(dir / name, gt);
  const std::vector<std::string> messages = {"pixels have no area", "non-finite",
                                             "latitude 1000"};
  for (std::size_t i = 0; i < rasters.size(); ++i) {
    const std::string input = quoted(dir / rasters[i].first);
    for (const std::string& command :
         {"info " + input, fmt::format("render {} -o {}", input, quoted(dir / "o.png")),
          fmt::format("build {} -o {}", input, quoted(dir / "o.tstore")),
          fmt::format("bench {} --path flyover --frames 2", input),
          fmt::format("bench {} --path walk --frames 2", input),
          fmt::format("bench {} --path orbit --frames 2", input),
          fmt::format("view {} --frames 1", input)}) {
      const RunResult result = runBounded(command);
      expectRefused(result, "has an unusable georeferencing", command);
      EXPECT_NE(result.output.find(messages[i]), std::string::npos) << result.output;
    }
  }
  EXPECT_EQ(filesIn(dir).size(), rasters.size()) << "an output was left behind";
}

// Class 4: a FIFO never blocks a command, a device is never replaced by a file.
TEST(Hostile, NonRegularFilesAreRefusedWithoutHanging) {
  const fs::path dir = test::freshTestDir();
  const fs::path fifo = dir / "fifo.hgt";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  const fs::path fifoJson = dir / "fifo.json";
  ASSERT_EQ(::mkfifo(fifoJson.c_str(), 0644), 0);
  const SmallTerrain t = makeSmallTerrain(dir);
  const std::string f = quoted(fifo);
  for (const std::string& command :
       {"info " + f, fmt::format("build {} -o {}", f, quoted(dir / "o.tstore")), "verify " + f,
        fmt::format("export {} -o {}", f, quoted(dir / "o.tif")),
        fmt::format("render {} -o {}", f, quoted(dir / "o.png")),
        fmt::format("bench {} --path {} --frames 2", quoted(t.dem), quoted(fifoJson))}) {
    expectRefused(runBounded(command, 20), "it is a FIFO, not a regular file", command);
  }
  // Devices as outputs: refused before any work, and left as they are. The test makes its own
  // null and full devices (root only) so that a regression cannot replace the system's.
  std::vector<std::string> left = {"fifo.hgt", "fifo.json", "t.tif", "t.tstore"};
  const fs::path null = dir / "null", full = dir / "full";
  if (::mknod(null.c_str(), S_IFCHR | 0666, makedev(1, 3)) != 0 ||
      ::mknod(full.c_str(), S_IFCHR | 0666, makedev(1, 7)) != 0) {
    GTEST_SKIP() << "cannot make device nodes here (not root?); FIFOs covered";
  }
  left.insert(left.begin() + 2, {"full", "null"});
  for (const fs::path& device : {null, full}) {
    for (const std::string& command :
         {fmt::format("render {} -o {} --size 64x48", quoted(t.dem), quoted(device)),
          fmt::format("generate -o {} --size 33", quoted(device)),
          fmt::format("export {} -o {}", quoted(t.store), quoted(device)),
          fmt::format("build {} -o {}", quoted(t.dem), quoted(device))}) {
      expectRefused(runBounded(command, 20), "it is a character device", command);
    }
    struct stat info {};
    ASSERT_EQ(::stat(device.c_str(), &info), 0);
    EXPECT_TRUE(S_ISCHR(info.st_mode)) << device << " was replaced";
  }
  EXPECT_EQ(filesIn(dir), left);
}

// Class 5: no output replaces an input, whatever name it is given by.
TEST(Hostile, OutputsNeverReplaceInputs) {
  const fs::path dir = test::freshTestDir();
  const SmallTerrain t = makeSmallTerrain(dir);
  fs::create_hard_link(t.dem, dir / "hardlink.tif");
  fs::create_symlink(t.store, dir / "symlink.tstore");
  const fs::path keys = dir / "keys.json";
  writeText(keys, R"({"keyframes": [
    {"time": 0, "position": [100, 100, 3000], "yaw": 45, "pitch": -30},
    {"time": 1, "position": [2000, 2000, 3000], "yaw": 45, "pitch": -30}]})");
  const std::string dem = contentOf(t.dem), store = contentOf(t.store), path = contentOf(keys);
  const std::string d = quoted(t.dem), s = quoted(t.store);
  for (const std::string& command :
       {fmt::format("render {} -o {}", d, d),
        fmt::format("render {} -o {}", d, quoted(dir / "hardlink.tif")),
        fmt::format("render {} -o {}", s, quoted(dir / "symlink.tstore")),
        fmt::format("export {} -o {}", s, s),
        fmt::format("export {} -o {}", s, quoted(dir / "symlink.tstore")),
        fmt::format("bench {} --frames 2 --json {}", d, d),
        fmt::format("bench {} --frames 2 --csv {}", d, quoted(dir / "hardlink.tif")),
        fmt::format("bench {} --path {} --frames 2 --json {}", d, quoted(keys), quoted(keys)),
        fmt::format("view {} --path {} --frames 2 --record {}", d, quoted(keys), quoted(keys)),
        fmt::format("build {} -o {}", d, d)}) {
    expectRefused(runBounded(command), "write the output elsewhere", command);
  }
  const RunResult twice = runBounded(fmt::format("bench {} --frames 2 --json {} --csv {}", d,
                                                 quoted(dir / "r.txt"), quoted(dir / "r.txt")));
  expectRefused(twice, "is given for two outputs", "the same file for --json and --csv");
  EXPECT_EQ(contentOf(t.dem), dem);
  EXPECT_EQ(contentOf(t.store), store);
  EXPECT_EQ(contentOf(keys), path);
  EXPECT_EQ(filesIn(dir), (std::vector<std::string>{"hardlink.tif", "keys.json", "symlink.tstore",
                                                    "t.tif", "t.tstore"}));
}

// Class 6: the plots folder's name reaches the plotting script as one argument, never through a
// shell; a failing plot step leaves no report behind.
TEST(Hostile, PlotFolderNamesAreNotShellCommands) {
  if (std::system("/usr/bin/python3 -c 'import matplotlib' >/dev/null 2>&1") != 0) {
    GTEST_SKIP() << "python3-matplotlib is not installed";
  }
  const fs::path dir = test::freshTestDir();
  ASSERT_EQ(runTellus(fmt::format("generate -o {} --size 65", quoted(dir / "t.tif"))).exitCode, 0);
  const std::string plots = "p'; touch INJECTED; echo '";
  const RunResult bench =
      runShell(fmt::format("cd {} && timeout 120 '{}' bench t.tif --frames 2 --size 96x64 --plots "
                           "\"{}\" --json r.json",
                           quoted(dir), TELLUS_EXECUTABLE, plots));
  ASSERT_EQ(bench.exitCode, 0) << bench.output;
  EXPECT_FALSE(fs::exists(dir / "INJECTED")) << "the folder name ran as a shell command";
  EXPECT_TRUE(fs::exists(dir / plots / "bench.json"));
  EXPECT_TRUE(fs::exists(dir / plots / "frame-reference-0000.png"));
  bool charts = false;
  for (const std::string& name : filesIn(dir / plots)) charts |= name == "frame_time.png";
  EXPECT_TRUE(charts) << "the plotting script wrote no charts";

  // A plotting script that fails (a matplotlib that raises on import): no plots, no JSON.
  const fs::path broken = dir / "broken-python";
  fs::create_directories(broken / "matplotlib");
  writeText(broken / "matplotlib" / "__init__.py", "raise ImportError('broken on purpose')\n");
  const RunResult failed = runShell(fmt::format(
      "cd {} && PYTHONPATH={} timeout 120 '{}' bench t.tif --frames 2 --size 96x64 --plots "
      "new-plots --json r2.json",
      quoted(dir), quoted(broken), TELLUS_EXECUTABLE));
  expectRefused(failed, "the plotting script failed", "bench with a broken matplotlib");
  EXPECT_FALSE(fs::exists(dir / "new-plots")) << "a half-written plots folder was left";
  EXPECT_FALSE(fs::exists(dir / "r2.json"));
}

// Class 7: a write that fails (file size limit, full disk) is reported and leaves nothing.
TEST(Hostile, FailedWritesAreReportedAndLeaveNothing) {
  const fs::path dir = test::freshTestDir();
  const SmallTerrain t = makeSmallTerrain(dir);
  const fs::path out = dir / "out";
  fs::create_directories(out);
  const std::vector<std::string> commands = {
      fmt::format("render {} -o {}/x.png --size 320x240", quoted(t.dem), quoted(out)),
      fmt::format("generate -o {}/x.tif --size 129", quoted(out)),
      fmt::format("export {} -o {}/x.tif", quoted(t.store), quoted(out)),
      fmt::format("build {} -o {}/x.tstore --tile 32", quoted(t.dem), quoted(out)),
      fmt::format("bench {} --frames 200 --size 64x48 --csv {}/x.csv", quoted(t.dem),
                  quoted(out)),
  };
  // A file size limit of 4 KiB (SIGXFSZ ignored, so writes fail with EFBIG).
  for (const std::string& command : commands) {
    const RunResult result = runShell(fmt::format("trap '' XFSZ; ulimit -f 8; timeout 60 '{}' {}",
                                                  TELLUS_EXECUTABLE, command));
    expectRefused(result, "cannot write", command);
    EXPECT_EQ(result.output.find("wrote"), std::string::npos) << command << result.output;
    EXPECT_TRUE(fs::is_empty(out)) << command << " left " << fmt::format("{}", fmt::join(filesIn(out), ", "));
  }
  // A really full disk: an 8 KiB tmpfs in a private mount namespace, where root may mount one.
  const RunResult probe = runShell("unshare -m sh -c 'mount -t tmpfs -o size=8k none /mnt'");
  if (probe.exitCode != 0) {
    GTEST_SKIP() << "cannot mount a small tmpfs here (" << probe.output << "); EFBIG covered";
  }
  for (const std::string& command : commands) {
    const RunResult result = runShell(fmt::format(
        "unshare -m sh -c \"mount -t tmpfs -o size=8k none {0} && timeout 60 '{1}' {2}; "
        "status=\\$?; ls -A {0} | sed 's/^/LEFT /'; exit \\$status\"",
        quoted(out), TELLUS_EXECUTABLE, command));
    expectRefused(result, "No space left on device", command);
    EXPECT_EQ(result.output.find("LEFT "), std::string::npos) << "a file was left: " << result.output;
  }
}

// Class 8: temporary files live in scratch folders or beside their output, and those of
// killed processes are swept by the next run.
TEST(Hostile, NoLitterInTheWorkingDirectoryAndStaleTemporariesAreSwept) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path dir = test::freshTestDir();
  const fs::path work = dir / "read-only-cwd";
  fs::create_directories(work);
  fs::permissions(work, fs::perms::owner_read | fs::perms::owner_exec);
  // N37E127 has 5 voids: filling them used to write GDAL work files into the current folder.
  const std::string hgt = quoted(data / "srtm3-hgt-east-asia/N37E127.hgt");
  const RunResult render = runShell(fmt::format(
      "cd {} && timeout 120 '{}' render {} -o {} --size 64x48", quoted(work), TELLUS_EXECUTABLE,
      hgt, quoted(dir / "x.png")));
  EXPECT_EQ(render.exitCode, 0) << render.output;
  EXPECT_TRUE(fs::is_empty(work)) << fmt::format("{}", fmt::join(filesIn(work), ", "));
  fs::permissions(work, fs::perms::owner_all);

  // Temporaries of a dead process (an exited child's pid) beside an output, and a scratch
  // folder of it, are removed by the next write there.
  const pid_t dead = ::fork();
  if (dead == 0) ::_exit(0);
  ::waitpid(dead, nullptr, 0);
  writeText(dir / fmt::format(".x.png.tellus-partial-{}-0", dead), "half a png");
  fs::create_directories(dir / fmt::format(".tellus-scratch-{}-0", dead));
  writeText(dir / fmt::format(".tellus-scratch-{}-0", dead) / "mask.tif", "scratch");
  writeText(dir / fmt::format(".t.tstore.tellus-partial-{}-3", dead), "half a store");
  // A live process' temporary is kept.
  writeText(dir / fmt::format(".x.png.tellus-partial-{}-0", ::getpid()), "in progress");
  EXPECT_EQ(runTellus(fmt::format("render {} -o {} --size 64x48", hgt, quoted(dir / "x.png")))
                .exitCode,
            0);
  ASSERT_EQ(runTellus(fmt::format("generate -o {} --size 65", quoted(dir / "t.tif"))).exitCode, 0);
  ASSERT_EQ(runTellus(fmt::format("build {} -o {}", quoted(dir / "t.tif"),
                                  quoted(dir / "t.tstore")))
                .exitCode,
            0);
  EXPECT_EQ(filesIn(dir),
            (std::vector<std::string>{fmt::format(".x.png.tellus-partial-{}-0", ::getpid()),
                                      "read-only-cwd", "t.tif", "t.tstore", "x.png"}));
}

// Class 9: what was expected and what was found, not "unknown GDAL error".
TEST(Hostile, UnreadableRastersAreExplained) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path dir = test::freshTestDir();
  const fs::path tile = data / "srtm3-hgt-east-asia/N37E127.hgt";
  writeText(dir / "empty.tif", "");
  const std::string srtm = contentOf(tile);
  writeText(dir / "N37E127.hgt", srtm.substr(0, srtm.size() - 1));
  writeText(dir / "renamed.hgt", srtm);
  std::string noise(5000, '\0');
  for (std::size_t i = 0; i < noise.size(); ++i) noise[i] = char((i * 2654435761u) >> 13);
  writeText(dir / "noise.tif", noise);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"empty.tif", "the file is empty (0 bytes)"},
      {"N37E127.hgt", "this file is 2884801 bytes, 1 fewer than an SRTM3 tile"},
      {"renamed.hgt", "has the size of a tile but the name 'renamed.hgt'"},
      {"noise.tif", "not in a raster format GDAL recognises (5000 bytes starting with"},
  };
  for (const auto& [file, message] : cases) {
    const RunResult result = runBounded("info " + quoted(dir / file));
    expectRefused(result, message, file);
    EXPECT_EQ(result.output.find("unknown GDAL error"), std::string::npos) << result.output;
  }
}

// Class 10: verify rejects stores whose checksums are right but whose content means nothing.
TEST(Hostile, VerifyRejectsChecksummedNonsense) {
  const fs::path dir = test::freshTestDir();
  const SmallTerrain t = makeSmallTerrain(dir);
  ASSERT_EQ(runTellus("verify " + quoted(t.store)).exitCode, 0);
  using Edit = std::function<void(test::StoreSections&)>;
  const auto record = [](test::StoreSections& s, int level) -> store_format::IndexRecord& {
    for (store_format::IndexRecord& r : s.index) {
      if (int(r.level) == level) return r;
    }
    return s.index.front();
  };
  const std::vector<std::tuple<std::string, Edit, std::string>> cases = {
      {"NaN geometric error", [&](auto& s) { record(s, 1).geometricErrorM = std::nanf(""); },
       "nonsensical geometric error"},
      {"negative geometric error", [&](auto& s) { record(s, 1).geometricErrorM = -3.0f; },
       "nonsensical geometric error"},
      {"infinite geometric error",
       [&](auto& s) { record(s, 1).geometricErrorM = INFINITY; }, "nonsensical geometric error"},
      {"tile min above max",
       [&](auto& s) { std::swap(record(s, 0).minHeightM, record(s, 0).maxHeightM); },
       "nonsensical height range"},
      {"store min above max",
       [](auto& s) { std::swap(s.metadata["min_height_m"], s.metadata["max_height_m"]); },
       "lowest height"},
      {"negative void count", [](auto& s) { s.metadata["filled_voids"] = -1; },
       "'filled_voids' is -1"},
      {"spacing 1e308", [](auto& s) { s.metadata["spacing_x_m"] = 1e308; }, "'spacing_x_m'"},
      {"CRS garbage", [](auto& s) { s.metadata["georef"]["crs_wkt"] = "PROJCS[garbage"; },
       "not valid WKT"},
      {"geotransform without area",
       [](auto& s) { s.metadata["georef"]["geotransform"][1] = 0.0; }, "pixels have no area"},
      {"quantum 0", [](auto& s) { s.metadata["quantum_m"] = 0.0; }, "'quantum_m' is 0"},
      {"levels that do not match", [](auto& s) { s.metadata["levels"][1]["tiles_x"] = 7; },
       "'levels' entry 1"},
  };
  for (const auto& [name, edit, message] : cases) {
    Result<test::StoreSections> sections = test::readStoreSections(t.store);
    ASSERT_TRUE(sections) << sections.error().message;
    edit(sections.value());
    const fs::path bad = dir / "bad.tstore";
    ASSERT_TRUE(test::writeStoreSections(sections.value(), bad));
    expectRefused(runBounded("verify " + quoted(bad)), message, name);
  }
  // Two tiles of a level whose payloads (with their checksums) trade places in the index.
  Result<test::StoreSections> swapped = test::readStoreSections(t.store);
  ASSERT_TRUE(swapped);
  test::swapTilePayloads(swapped.value(), 0, 1);
  ASSERT_TRUE(test::writeStoreSections(swapped.value(), dir / "swapped.tstore", false));
  const RunResult verify = runBounded("verify " + quoted(dir / "swapped.tstore"));
  expectRefused(verify, "tile 0/0/0 (level/x/y) is corrupt (checksum mismatch)", "swapped tiles");
  EXPECT_NE(verify.output.find("tile 0/1/0 (level/x/y) is corrupt"), std::string::npos);
  // A version 1 store is refused with the way out.
  Result<test::StoreSections> old = test::readStoreSections(t.store);
  ASSERT_TRUE(old);
  old->header.version = 1;
  ASSERT_TRUE(test::writeStoreSections(old.value(), dir / "v1.tstore"));
  expectRefused(runBounded("info " + quoted(dir / "v1.tstore")),
                "is a version 1 tile store, written before tile keys were bound", "version 1");
}

}  // namespace
}  // namespace tellus
