// Hostile input on the surfaces added after the first hardening pass (the global store, .tstack,
// .bdam, glTF and quantized-mesh export, stores over HTTP), class by class, end to end through
// the tellus binary: data loss, hangs, crashes, wrong successes and messages. Every refusal
// must be one clear error naming the file, a status from 1 to 127 within seconds, and no input
// changed.
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <future>
#include <limits>
#include <map>
#include <optional>
#include <tuple>

#include <fmt/format.h>
#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogr_spatialref.h>

#include "cli/hostile_support.hpp"
#include "support/misbehaving_http_server.hpp"
#include "support/store_surgery.hpp"
#include "support/test_support.hpp"
#include "tellus/formats/stacks/material_stack.hpp"
#include "tellus/formats/stacks/stack_aggregation.hpp"
#include "tellus/formats/stacks/stack_file.hpp"

namespace tellus {
namespace {
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Every regular file under `folder` with its content, for "nothing changed".
std::map<std::string, std::string> snapshot(const fs::path& folder) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(folder)) {
    if (entry.is_regular_file()) files[entry.path().lexically_relative(folder).string()] = contentOf(entry.path());
  }
  return files;
}

// A one-band Float32 GeoTIFF in WGS 84 of `value` everywhere (NaN, infinity, a nodata value).
void writeConstantGeoTiff(const fs::path& file, float value, std::optional<double> nodata,
                          int width = 33, int height = 33,
                          std::array<double, 6> gt = {127.0, 0.01, 0.0, 37.5, 0.0, -0.01}) {
  GDALAllRegister();
  GDALDataset* ds = GetGDALDriverManager()->GetDriverByName("GTiff")->Create(
      file.c_str(), width, height, 1, GDT_Float32, nullptr);
  ASSERT_NE(ds, nullptr);
  ds->SetGeoTransform(gt.data());
  OGRSpatialReference wgs84;
  wgs84.importFromEPSG(4326);
  ds->SetSpatialRef(&wgs84);
  if (nodata) ds->GetRasterBand(1)->SetNoDataValue(*nodata);
  std::vector<float> values(std::size_t(width) * std::size_t(height), value);
  ASSERT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, width, height, values.data(), width,
                                           height, GDT_Float32, 0, 0),
            CE_None);
  GDALClose(ds);
}

// A .tstack of the small terrain and its bytes.
fs::path makeStackFile(const fs::path& dir, const SmallTerrain& t) {
  const fs::path stack = dir / "s.tstack";
  const RunResult built = runTellus(fmt::format("stacks build {} -o {}", quoted(t.dem), quoted(stack)));
  EXPECT_EQ(built.exitCode, 0) << built.output;
  return stack;
}

// Class 1: an output folder replaces only a tile set Tellus wrote, never one holding anything
// else or an input, never the current folder; the old set is swapped out, never lost.
TEST(HostileSurfaces, OutputFoldersNeverReplaceWhatTellusDidNotWrite) {
  const fs::path dir = test::freshTestDir();
  const SmallTerrain t = makeSmallTerrain(dir);
  ASSERT_EQ(runTellus(fmt::format("export {} --quantized-mesh {}", quoted(t.store), quoted(dir / "old")))
                .exitCode,
            0);
  ASSERT_TRUE(fs::exists(dir / "old" / ".tellus-tileset"));
  // A copy of the tile set with the input store inside it (the issue's case).
  fs::copy(dir / "old", dir / "qm", fs::copy_options::recursive);
  fs::copy_file(t.store, dir / "qm" / "s.tstore");
  const auto before = snapshot(dir / "qm");
  expectRefused(runBounded(fmt::format("export {} --quantized-mesh {}", quoted(dir / "qm" / "s.tstore"),
                                       quoted(dir / "qm"))),
                "holds the input", "a tile set holding its input");
  EXPECT_EQ(snapshot(dir / "qm"), before);
  // The current folder, with a layer.json and other files: never replaced.
  fs::copy(dir / "old", dir / "here", fs::copy_options::recursive);
  fs::remove(dir / "here" / ".tellus-tileset");
  writeText(dir / "here" / "notes.txt", "mine");
  fs::create_directories(dir / "here" / "sub");
  writeText(dir / "here" / "sub" / "data.bin", "also mine");
  const auto here = snapshot(dir / "here");
  const RunResult dot = runShell(fmt::format("cd {} && timeout -s KILL 60 '{}' export {} --quantized-mesh .",
                                             quoted(dir / "here"), TELLUS_EXECUTABLE, quoted(t.store)));
  expectRefused(dot, "current folder", "--quantized-mesh .");
  EXPECT_EQ(snapshot(dir / "here"), here);
  // A tile set of Tellus's with something else put into it: refused, that thing named.
  fs::create_directories(dir / "old" / "docs");
  writeText(dir / "old" / "docs" / "notes.txt", "keep me");
  expectRefused(runBounded(fmt::format("export {} --quantized-mesh {}", quoted(t.store), quoted(dir / "old"))),
                "holds 'docs'", "a foreign file in a tile set");
  EXPECT_EQ(contentOf(dir / "old" / "docs" / "notes.txt"), "keep me");
  // A tile set without the marker (an older Tellus's, or another tool's): not Tellus's.
  fs::copy(dir / "old", dir / "nomarker", fs::copy_options::recursive);
  fs::remove(dir / "nomarker" / ".tellus-tileset");
  fs::remove_all(dir / "nomarker" / "docs");
  expectRefused(runBounded(fmt::format("export {} --quantized-mesh {}", quoted(t.store), quoted(dir / "nomarker"))),
                "has no '.tellus-tileset' marker", "a tile set Tellus did not mark");
  // A device.
  expectRefused(runBounded(fmt::format("export {} --quantized-mesh /dev/null", quoted(t.store))),
                "it is a character device, not a folder", "/dev/null");
  // Its own tile set is replaced whole; the temporaries of killed exports (this version's and
  // the earlier ".NAME.tmp-PID") are swept, nothing else is left beside it.
  fs::remove_all(dir / "old" / "docs");
  const pid_t dead = [] {
    const pid_t pid = ::fork();
    if (pid == 0) ::_exit(0);
    ::waitpid(pid, nullptr, 0);
    return pid;
  }();
  fs::copy(dir / "old", dir / fmt::format(".old.tmp-{}", dead), fs::copy_options::recursive);
  fs::remove(dir / fmt::format(".old.tmp-{}", dead) / ".tellus-tileset");
  fs::create_directories(dir / fmt::format(".old.tellus-partial-{}-0", dead) / "3");
  const RunResult again = runBounded(fmt::format("export {} --quantized-mesh {}", quoted(t.store), quoted(dir / "old")));
  EXPECT_EQ(again.exitCode, 0) << again.output;
  EXPECT_TRUE(fs::exists(dir / "old" / "layer.json"));
  EXPECT_FALSE(fs::exists(dir / fmt::format(".old.tmp-{}", dead)));
  EXPECT_FALSE(fs::exists(dir / fmt::format(".old.tellus-partial-{}-0", dead)));
}

// Class 1: an export killed at any moment, the swap included, leaves a complete tile set.
TEST(HostileSurfaces, AKilledExportLeavesACompleteTileSet) {
  const fs::path dir = test::freshTestDir();
  const SmallTerrain t = makeSmallTerrain(dir);
  ASSERT_EQ(runTellus(fmt::format("export {} --quantized-mesh {}", quoted(t.store), quoted(dir / "qm"))).exitCode, 0);
  const std::size_t tiles = [&] {
    std::size_t n = 0;
    for (const auto& e : fs::recursive_directory_iterator(dir / "qm")) n += e.path().extension() == ".terrain";
    return n;
  }();
  const auto complete = [&](const std::string& when) {
    std::size_t n = 0;
    for (const auto& e : fs::recursive_directory_iterator(dir / "qm")) n += e.path().extension() == ".terrain";
    EXPECT_EQ(n, tiles) << when;
    EXPECT_TRUE(fs::exists(dir / "qm" / "layer.json")) << when;
    EXPECT_TRUE(fs::exists(dir / "qm" / ".tellus-tileset")) << when;
  };
  // Killed exactly at the swap (strace injects SIGKILL at the renameat2 that exchanges them).
  if (std::system("command -v strace >/dev/null 2>&1") == 0) {
    const RunResult swap = runShell(fmt::format(
        "strace -f -qq -o /dev/null -e trace=renameat2 -e inject=renameat2:signal=KILL '{}' export {} "
        "--quantized-mesh {}",
        TELLUS_EXECUTABLE, quoted(t.store), quoted(dir / "qm")));
    EXPECT_NE(swap.exitCode, 0) << "the kill must have happened: " << swap.output;
    complete("killed at the swap");
  }
  // Killed at times through the export.
  for (int ms : {30, 80, 150, 250, 400}) {
    runShell(fmt::format("timeout -s KILL {:.3f} '{}' export {} --quantized-mesh {}", ms / 1000.0,
                         TELLUS_EXECUTABLE, quoted(t.store), quoted(dir / "qm")));
    complete(fmt::format("killed after {} ms", ms));
  }
  // The next export sweeps what the kills left.
  ASSERT_EQ(runTellus(fmt::format("export {} --quantized-mesh {}", quoted(t.store), quoted(dir / "qm"))).exitCode, 0);
  for (const auto& e : fs::directory_iterator(dir)) {
    EXPECT_EQ(e.path().filename().string().find(".tellus-"), std::string::npos) << e.path();
  }
}

// Class 1: every file a command reads is protected like its positional inputs.
TEST(HostileSurfaces, EveryFileACommandReadsIsProtected) {
  const fs::path dir = test::freshTestDir();
  const SmallTerrain t = makeSmallTerrain(dir);
  ASSERT_EQ(runTellus(fmt::format("build {} -o {} --bdam", quoted(t.dem), quoted(dir / "x.tstore"))).exitCode, 0);
  const std::string patches = contentOf(dir / "x.bdam");
  expectRefused(runBounded(fmt::format("render {} --algo bdam -o {}", quoted(dir / "x.tstore"), quoted(dir / "x.bdam"))),
                "it is the input", "the default patch file as the PNG");
  EXPECT_EQ(contentOf(dir / "x.bdam"), patches);
  fs::copy_file(dir / "x.bdam", dir / "p.bdam");
  expectRefused(runBounded(fmt::format("render {} --algo bdam --bdam-patches {} -o {}", quoted(dir / "x.tstore"),
                                       quoted(dir / "p.bdam"), quoted(dir / "p.bdam"))),
                "it is the input", "--bdam-patches as the PNG");
  // Files named by options (checked before anything is loaded: any content will do).
  writeText(dir / "g.gtx", "a geoid");
  writeText(dir / "d.jpg", "a drape");
  expectRefused(runBounded(fmt::format("bench {} --geoid {} --json {} --frames 1", quoted(t.store),
                                       quoted(dir / "g.gtx"), quoted(dir / "g.gtx"))),
                "it is the input", "--geoid as --json");
  expectRefused(runBounded(fmt::format("render {} --drape {} -o {}", quoted(t.store), quoted(dir / "d.jpg"),
                                       quoted(dir / "d.jpg"))),
                "it is the input", "--drape as -o");
  EXPECT_EQ(contentOf(dir / "g.gtx"), "a geoid");
  EXPECT_EQ(contentOf(dir / "d.jpg"), "a drape");
  // An input named like the patch writer's temporary of old ("x.bdam.part") is kept.
  fs::copy_file(t.dem, dir / "y.bdam.part");
  const std::string dem = contentOf(dir / "y.bdam.part");
  const RunResult part = runBounded(fmt::format("build {} -o {} --bdam", quoted(dir / "y.bdam.part"), quoted(dir / "y.tstore")));
  EXPECT_EQ(part.exitCode, 0) << part.output;
  EXPECT_EQ(contentOf(dir / "y.bdam.part"), dem);
  EXPECT_TRUE(fs::exists(dir / "y.tstore") && fs::exists(dir / "y.bdam"));
  // The patch file cannot be written (a file size limit between the store's size and the
  // patches'): neither is written, and the message says why.
  const RunResult limited = runShell(fmt::format("trap '' XFSZ; ulimit -f 60; timeout -s KILL 60 '{}' build {} -o {} --bdam",
                                                 TELLUS_EXECUTABLE, quoted(t.dem), quoted(dir / "z.tstore")));
  expectRefused(limited, "File too large", "patch file over the size limit");
  EXPECT_NE(limited.output.find("z.tstore was not written either"), std::string::npos) << limited.output;
  EXPECT_FALSE(fs::exists(dir / "z.tstore"));
  EXPECT_FALSE(fs::exists(dir / "z.bdam"));
}

// Class 2: a server that does not answer, loops, stalls or trickles costs one deadline (25 s
// by default), not minutes; the URL is not asked again, and verify stops at the first dead read.
TEST(HostileSurfaces, HttpStoresGiveUpWithinTheDeadline) {
  const fs::path dir = test::freshTestDir();
  const SmallTerrain t = makeSmallTerrain(dir);
  // The default deadline (25 s) runs beside the other cases.
  auto silentDefault = test::MisbehavingHttpServer::start(test::Misbehaviour::Silent);
  ASSERT_TRUE(silentDefault);
  const auto defaultStart = Clock::now();
  std::future<RunResult> defaultRun = std::async(std::launch::async, [&] {
    return runBounded("info " + silentDefault->url("t.tstore"), 90);
  });
  // The others with a shorter deadline, from the environment and from --http-deadline.
  const std::string fast = "TELLUS_HTTP_DEADLINE_MS=3000 TELLUS_HTTP_LOW_SPEED_S=2 ";
  struct Case {
    test::Misbehaviour behaviour;
    std::string message;
  };
  for (const Case& c : {Case{test::Misbehaviour::RedirectLoop, "more than 10 redirects"},
                        Case{test::Misbehaviour::HeadersThenSilence, "stalled"},
                        Case{test::Misbehaviour::Trickle, "stalled"}}) {
    auto server = test::MisbehavingHttpServer::start(c.behaviour);
    ASSERT_TRUE(server);
    const auto start = Clock::now();
    const RunResult info = runShell(fmt::format("{}timeout -s KILL 60 '{}' info {}", fast, TELLUS_EXECUTABLE,
                                                server->url("t.tstore")));
    expectRefused(info, c.message, c.message);
    EXPECT_LT(secondsSince(start), 8.0) << c.message;
    if (c.behaviour == test::Misbehaviour::RedirectLoop) {
      EXPECT_LE(server->requests(), 11);
    }
  }
  {
    auto silent = test::MisbehavingHttpServer::start(test::Misbehaviour::Silent);
    const auto start = Clock::now();
    expectRefused(runBounded(fmt::format("--http-deadline 2 info {}", silent->url("t.tstore"))),
                  "does not answer", "--http-deadline 2");
    EXPECT_LT(secondsSince(start), 6.0);
  }
  // A store whose header, metadata and index come, then nothing: verify gives up at once.
  Result<test::StoreSections> sections = test::readStoreSections(t.store);
  ASSERT_TRUE(sections);
  const std::uint64_t tilesFrom = store_format::kHeaderBytes;
  auto stalling = test::MisbehavingHttpServer::start(test::Misbehaviour::StallOnRange, t.store, tilesFrom,
                                                     tilesFrom + sections->payloads.size());
  const auto start = Clock::now();
  const RunResult verify = runShell(fmt::format("{}timeout -s KILL 60 '{}' verify {}", fast, TELLUS_EXECUTABLE,
                                                stalling->url("t.tstore")));
  expectRefused(verify, "stopped answering", "verify of a stalled server");
  EXPECT_LT(secondsSince(start), 10.0);
  const RunResult silentInfo = defaultRun.get();
  expectRefused(silentInfo, "the server does not answer", "a silent server, default limits");
  EXPECT_LT(secondsSince(defaultStart), 30.0);
  EXPECT_LE(silentDefault->requests(), 4) << "the URL is tried once, with its retries, not once per open";
}

// Class 2: what cannot finish is refused with the figures; long work reports progress in logs.
TEST(HostileSurfaces, WorkThatCannotFinishIsRefusedAndLongWorkIsNotSilent) {
  const fs::path dir = test::freshTestDir();
  const SmallTerrain t = makeSmallTerrain(dir);
  ASSERT_EQ(::mkfifo((dir / "geoid.fifo").c_str(), 0600), 0);
  const auto start = Clock::now();
  expectRefused(runBounded(fmt::format("bench {} --geoid {} --frames 1", quoted(t.store), quoted(dir / "geoid.fifo")), 20),
                "FIFO", "a FIFO as --geoid");
  expectRefused(runBounded(fmt::format("stacks build {} -o {} --spacing 1e-6", quoted(t.dem), quoted(dir / "s.tstack")), 20),
                "give a --spacing of at least", "stacks at a micrometre");
  expectRefused(runBounded(fmt::format("export {} --quantized-mesh {} --max-level 20", quoted(t.store),
                                       quoted(dir / "qm")), 20),
                "levels finer than", "--max-level 20");
  EXPECT_FALSE(fs::exists(dir / "qm"));
  EXPECT_LT(secondsSince(start), 20.0);
  // A build of a 100000 x 100000 raster (sparse on disk) with stderr to a pipe: progress lines.
  writeSparseHugeGeoTiff(dir / "huge.tif");
  for (const std::string& command : {fmt::format("build {} -o {} --tile 512", quoted(dir / "huge.tif"), quoted(dir / "h.tstore")),
                                     fmt::format("build --global {} -o {}", quoted(dir / "huge.tif"), quoted(dir / "hg.tstore"))}) {
    const RunResult run = runShell(fmt::format("TELLUS_PROGRESS_LOG_SECONDS=1 timeout -s KILL 5 '{}' {}",
                                               TELLUS_EXECUTABLE, command));
    EXPECT_NE(run.output.find("% ("), std::string::npos) << command << ":\n" << run.output;
    EXPECT_NE(run.output.find(" left"), std::string::npos) << command << ":\n" << run.output;
  }
}

// Class 3: a .tstack's spacing is checked where it is read, by every command (1e300 crashed
// bench, 1e-300 drew a blank image with exit 0).
TEST(HostileSurfaces, StackFilesWithAbsurdSpacingsAreRefusedEverywhere) {
  const fs::path dir = test::freshTestDir();
  const SmallTerrain t = makeSmallTerrain(dir);
  const std::string good = contentOf(makeStackFile(dir, t));
  for (const double spacing : {1e300, 1e-300}) {
    std::string bytes = good;
    std::memcpy(bytes.data() + 16, &spacing, 8);
    test::resealStackHeader(bytes);
    const fs::path forged = dir / "forged.tstack";
    writeText(forged, bytes);
    for (const std::string& command :
         {fmt::format("bench {} --frames 2 --size 64x48", quoted(forged)),
          fmt::format("render {} -o {} --size 64x48", quoted(forged), quoted(dir / "o.png")),
          fmt::format("verify {}", quoted(forged)), fmt::format("info {}", quoted(forged))}) {
      expectRefused(runBounded(command), "forged.tstack': its sample spacing", command);
    }
    EXPECT_FALSE(fs::exists(dir / "o.png"));
  }
}

// Class 4: nothing that is wrong ends with exit 0.
TEST(HostileSurfaces, WrongResultsAreErrors) {
  const fs::path dir = test::freshTestDir();
  const SmallTerrain t = makeSmallTerrain(dir);
  // Global stores: lossless only; sources without one valid height refused.
  writeSmallGeoTiff(dir / "src.tif", {127.0, 0.01, 0.0, 37.5, 0.0, -0.01});
  expectRefused(runBounded(fmt::format("build --global {} -o {} --codec lerc --max-error 1",
                                       quoted(dir / "src.tif"), quoted(dir / "lossy.tstore"))),
                "--global stores are lossless", "a lossy global build");
  writeConstantGeoTiff(dir / "nan.tif", std::numeric_limits<float>::quiet_NaN(), std::nullopt);
  writeConstantGeoTiff(dir / "inf.tif", std::numeric_limits<float>::infinity(), std::nullopt);
  writeConstantGeoTiff(dir / "nodata.tif", -32768.0f, -32768.0);
  for (const char* name : {"nan.tif", "inf.tif", "nodata.tif"}) {
    expectRefused(runBounded(fmt::format("build --global {} -o {}", quoted(dir / name), quoted(dir / "g0.tstore"))),
                  "no source has a valid height", name);
    EXPECT_FALSE(fs::exists(dir / "g0.tstore")) << name;
  }
  // A global store whose metadata lists no source.
  ASSERT_EQ(runTellus(fmt::format("build --global {} -o {} --tile 16 --max-depth 5", quoted(dir / "src.tif"),
                                  quoted(dir / "g.tstore"))).exitCode, 0);
  Result<test::StoreSections> sections = test::readStoreSections(dir / "g.tstore");
  ASSERT_TRUE(sections);
  sections->metadata["sources"] = nlohmann::json::array();
  ASSERT_TRUE(test::writeStoreSections(sections.value(), dir / "nosources.tstore"));
  expectRefused(runBounded("verify " + quoted(dir / "nosources.tstore")), "lists no source", "sources: []");
  // BDAM: a corrupt patch is an error in render and bench, and no image is written.
  ASSERT_EQ(runTellus(fmt::format("build {} -o {} --bdam", quoted(t.dem), quoted(dir / "x.tstore"))).exitCode, 0);
  const test::BdamParts good = test::readBdamParts(dir / "x.bdam");
  test::BdamParts parts = good;
  ASSERT_FALSE(parts.data.empty());
  for (std::size_t at = 16; at < parts.data.size(); at += 997) parts.data[at] ^= std::byte{0x5a};
  {
    std::ofstream out(dir / "x.bdam", std::ios::binary | std::ios::trunc);
    for (const auto* part : {&parts.header, &parts.table, &parts.data}) {
      out.write(reinterpret_cast<const char*>(part->data()), std::streamsize(part->size()));
    }
  }
  expectRefused(runBounded(fmt::format("render {} --algo bdam -o {} --size 96x64", quoted(dir / "x.tstore"),
                                       quoted(dir / "b.png"))),
                "fails its checksum", "render of flipped patches");
  EXPECT_FALSE(fs::exists(dir / "b.png"));
  expectRefused(runBounded(fmt::format("bench {} --algo bdam --frames 3 --size 96x64", quoted(dir / "x.tstore"))),
                "fails its checksum", "bench of flipped patches");
  if (haveXvfb()) {  // the viewer shows the error, goes on, and exits 1
    expectRefused(runViewUnderXvfb(fmt::format("{} --algo bdam --frames 3 --size 96x64 --no-panel",
                                               quoted(dir / "x.tstore"))),
                  "fails its checksum", "view of flipped patches");
  }
  // The same patches with their checksums recomputed over a NaN height in each (the first
  // vertex's: bytes 4 to 8 of each patch's data).
  parts = good;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::uint64_t dataStart = parts.header.size() + parts.table.size();
  for (std::size_t entry = 0; entry + 56 <= parts.table.size(); entry += 56) {
    std::uint64_t offset = 0;
    std::memcpy(&offset, parts.table.data() + entry + 8, 8);
    std::memcpy(parts.data.data() + (offset - dataStart) + 4, &nan, 4);
  }
  test::writeBdamParts(parts, dir / "x.bdam");
  expectRefused(runBounded(fmt::format("render {} --algo bdam -o {} --size 96x64", quoted(dir / "x.tstore"),
                                       quoted(dir / "b.png"))),
                "height nan m", "render of NaN heights");
  // .tstack: bytes appended; a level that is not the aggregation of the one below.
  const fs::path stack = makeStackFile(dir, t);
  writeText(dir / "appended.tstack", contentOf(stack) + std::string(4096, 'x'));
  expectRefused(runBounded("verify " + quoted(dir / "appended.tstack")), "4096 bytes follow", "appended bytes");
  Result<std::vector<StackTerrain>> levels = readStackFile(stack);
  ASSERT_TRUE(levels);
  std::vector<StackLayer> raised = levels->at(1).layers();  // another material everywhere
  for (StackLayer& layer : raised) layer.material = StackMaterial(layer.material == 7 ? 8 : 7);
  Result<StackTerrain> level1 = StackTerrain::fromArrays(levels->at(1).width(), levels->at(1).height(),
                                                         levels->at(1).spacingM(), levels->at(1).offsets(), raised);
  ASSERT_TRUE(level1) << level1.error().message;
  (*levels)[1] = std::move(level1.value());
  ASSERT_TRUE(writeStackFile(dir / "level1.tstack", levels.value()));
  expectRefused(runBounded("verify " + quoted(dir / "level1.tstack")), "level 1 is not the aggregation of level 0",
                "an inconsistent level 1");
  // Options given empty are mistakes, not defaults.
  expectRefused(runBounded(fmt::format("render {} --geo-camera \"\" -o {}", quoted(dir / "g.tstore"), quoted(dir / "o.png"))),
                "an empty value", "--geo-camera \"\"");
  // Sphere edits far beyond the terrain, and edits that change nothing.
  expectRefused(runBounded(fmt::format("stacks edit {} --sphere 100,100,100,1e30 --remove -o {}", quoted(stack),
                                       quoted(dir / "e.tstack"))),
                "far beyond the terrain", "radius 1e30");
  expectRefused(runBounded(fmt::format("stacks edit {} --sphere 100,100,3000,10 --remove -o {}", quoted(stack),
                                       quoted(dir / "e.tstack"))),
                "changes no stack", "an edit in the sky");
  EXPECT_FALSE(fs::exists(dir / "e.tstack"));
  // --max-samples below what the coarsest level needs.
  expectRefused(runBounded(fmt::format("export {} --gltf {} --max-samples 4", quoted(t.store), quoted(dir / "m.glb"))),
                "more than --max-samples 4", "--max-samples 4");
  EXPECT_FALSE(fs::exists(dir / "m.glb"));
  // A CRS that does not parse: every command, not only verify.
  Result<test::StoreSections> crs = test::readStoreSections(t.store);
  ASSERT_TRUE(crs);
  crs->metadata["georef"]["crs_wkt"] = "GARBAGE[\"not a coordinate system\"]";
  ASSERT_TRUE(test::writeStoreSections(crs.value(), dir / "crs.tstore"));
  for (const std::string& command : {fmt::format("info {}", quoted(dir / "crs.tstore")),
                                     fmt::format("render {} -o {} --size 64x48", quoted(dir / "crs.tstore"), quoted(dir / "o.png")),
                                     fmt::format("export {} -o {}", quoted(dir / "crs.tstore"), quoted(dir / "o.tif"))}) {
    expectRefused(runBounded(command), "georeferencing is unusable", command);
  }
  // Two tiles swapped with their checksums, min/max and the index recomputed.
  Result<test::StoreSections> swapped = test::readStoreSections(t.store);
  ASSERT_TRUE(swapped);
  test::swapTilePayloads(swapped.value(), 0, 1);
  ASSERT_TRUE(test::writeStoreSections(swapped.value(), dir / "swapped.tstore", true));
  expectRefused(runBounded("verify " + quoted(dir / "swapped.tstore")), "a tile out of place", "swapped tiles");
}

// Class 5: every message names the file, what is wrong and, where it helps, what to do.
TEST(HostileSurfaces, MessagesNameTheFileAndTheCause) {
  const fs::path dir = test::freshTestDir();
  const SmallTerrain t = makeSmallTerrain(dir);
  writeText(dir / "notes.txt", "these are notes, not a raster\n");
  writeText(dir / "notes.gtx", "these are notes, not a geoid\n");
  writeText(dir / "notes.jpg", "these are notes, not an image\n");
  writeSmallGeoTiff(dir / "src.tif", {127.0, 0.01, 0.0, 37.5, 0.0, -0.01});
  ASSERT_EQ(runTellus(fmt::format("build --global {} -o {} --tile 16 --max-depth 5", quoted(dir / "src.tif"),
                                  quoted(dir / "g.tstore"))).exitCode, 0);
  const std::string camera = "--geo-camera 37.3,127.1,20000,0,-60,50";
  for (const auto& [command, file] : std::vector<std::pair<std::string, std::string>>{
           {fmt::format("build --global {} -o {}", quoted(dir / "notes.txt"), quoted(dir / "n.tstore")), "notes.txt"},
           {fmt::format("render {} --algo globe-reference {} --geoid {} -o {}", quoted(dir / "g.tstore"), camera,
                        quoted(dir / "notes.gtx"), quoted(dir / "o.png")), "notes.gtx"},
           {fmt::format("render {} --algo globe-reference {} --drape {} -o {}", quoted(dir / "g.tstore"), camera,
                        quoted(dir / "notes.jpg"), quoted(dir / "o.png")), "notes.jpg"},
           {fmt::format("export {} --quantized-mesh {} --geoid {}", quoted(t.store), quoted(dir / "qm"),
                        quoted(dir / "notes.gtx")), "notes.gtx"}}) {
    const RunResult run = runBounded(command);
    expectRefused(run, "not in a raster format GDAL recognises", command);
    EXPECT_NE(run.output.find(file), std::string::npos) << run.output;
    EXPECT_EQ(run.output.find("unknown GDAL error"), std::string::npos) << run.output;
  }
  // Pixel sizes of 0 and NaN (GDAL keeps them in a VRT, not in a GeoTIFF): said as such, for
  // a global source and for a geoid.
  for (const auto& [name, pixel, message] : std::vector<std::tuple<std::string, std::string, std::string>>{
           {"zero.vrt", "0", "its pixel size is 0 x -0.01"},
           {"nanpx.vrt", "nan", "its geotransform has a non-finite number"}}) {
    writeText(dir / name, fmt::format(R"(<VRTDataset rasterXSize="33" rasterYSize="33">
  <SRS>EPSG:4326</SRS><GeoTransform>127, {}, 0, 37.5, 0, -0.01</GeoTransform>
  <VRTRasterBand dataType="Int16" band="1"><SimpleSource>
    <SourceFilename relativeToVRT="1">src.tif</SourceFilename><SourceBand>1</SourceBand>
  </SimpleSource></VRTRasterBand></VRTDataset>)", pixel));
    expectRefused(runBounded(fmt::format("build --global {} -o {}", quoted(dir / name), quoted(dir / "z.tstore"))),
                  name + "': " + message, name + " as a source");
    expectRefused(runBounded(fmt::format("export {} --quantized-mesh {} --geoid {}", quoted(t.store),
                                         quoted(dir / "qm"), quoted(dir / name))),
                  name + "': " + message, name + " as a geoid");
  }
  // A source of one row (its box has no height): the file is named.
  writeConstantGeoTiff(dir / "row.tif", 100.0f, std::nullopt, 33, 1);
  expectRefused(runBounded(fmt::format("build --global {} -o {}", quoted(dir / "row.tif"), quoted(dir / "z.tstore"))),
                "row.tif' is 33 x 1 samples", "one row");
  // A FIFO as --bdam-patches is a FIFO, not "does not exist".
  ASSERT_EQ(::mkfifo((dir / "patches.fifo").c_str(), 0600), 0);
  expectRefused(runBounded(fmt::format("render {} --algo bdam --bdam-patches {} -o {}", quoted(t.store),
                                       quoted(dir / "patches.fifo"), quoted(dir / "o.png")), 20),
                "it is a FIFO", "a FIFO as --bdam-patches");
  // 200-byte stack files that declare 1 GiB and 16 GiB: refused at once, under a 256 MiB budget.
  const std::string good = contentOf(makeStackFile(dir, t));
  for (const std::uint64_t declared : {std::uint64_t(1) << 30, std::uint64_t(16) << 30}) {
    // One level of 2^k columns (+ 1 offset) x 4 bytes = the declared size, in a 17-byte frame.
    const std::uint64_t columns = declared / 4 - 1;
    const std::uint32_t width = 16385, height = std::uint32_t(columns / 16385);
    const std::uint64_t raw = (std::uint64_t(width) * height + 1) * 4;
    std::string bytes = good.substr(0, 64 + 48);
    // A version 1 header (the file made above keeps its DEM's georeference: version 2).
    const std::uint32_t one = 1;
    const std::uint64_t noGeoreference = 0;
    std::memcpy(bytes.data() + 8, &one, 4);
    std::memcpy(bytes.data() + 32, &noGeoreference, 8);
    std::memcpy(bytes.data() + 12, &one, 4);
    std::memcpy(bytes.data() + 64, &width, 4);
    std::memcpy(bytes.data() + 68, &height, 4);
    const std::uint64_t layers = 0, offset = 64 + 48, frameBytes = 17;
    std::memcpy(bytes.data() + 72, &layers, 8);
    std::memcpy(bytes.data() + 80, &offset, 8);
    std::memcpy(bytes.data() + 88, &frameBytes, 8);
    std::string frame = "\x28\xb5\x2f\xfd\xe0";
    frame.append(reinterpret_cast<const char*>(&raw), 8);
    frame += std::string("\x03\x00\x01\x00", 4);
    bytes += frame;
    test::resealStackHeader(bytes);
    writeText(dir / "declared.tstack", bytes);
    const auto start = Clock::now();
    const RunResult verify = runShell(fmt::format("TELLUS_MEMORY_LIMIT_MB=256 timeout -s KILL 30 '{}' verify {}",
                                                  TELLUS_EXECUTABLE, quoted(dir / "declared.tstack")));
    expectRefused(verify, "declared.tstack': level 0's block of 17 bytes declares", "a 129-byte stack file");
    EXPECT_EQ(verify.output.find("out of memory"), std::string::npos) << verify.output;
    EXPECT_LT(secondsSince(start), 5.0);
  }
}

}  // namespace
}  // namespace tellus
