// Recording a flown path: keyframes at the recorder's interval plus the last camera, times
// relative to the start, a JSON round trip that replays the flight, and a clear error for a
// recording too short to be a path; on the globe, lat/lon keyframes that read back. The frame history behind the viewer's graph keeps the last
// frames in order and fills in late GPU times.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "support/test_support.hpp"
#include "tellus/viewer/frame_history.hpp"
#include "tellus/viewer/path_recorder.hpp"

namespace tellus {
namespace {

// A flight east at 100 m/s, turning 10 degrees per second.
Camera flight(double t) {
  Camera c;
  c.position = {100.0 * t, 0.0, 500.0};
  c.yawDeg = 90.0 + 10.0 * t;
  c.pitchDeg = -10.0;
  c.fovYDeg = 50.0;
  return c;
}

TEST(PathRecorder, KeepsAKeyframePerIntervalAndTheLastCamera) {
  PathRecorder recorder(0.25);
  recorder.add(0.0, flight(0.0));  // not recording yet: ignored
  recorder.start(100.0);
  for (int frame = 0; frame <= 160; ++frame) {  // 60 frames per second for 2.67 s
    const double t = frame / 60.0;
    recorder.add(100.0 + t, flight(t));
  }
  EXPECT_TRUE(recorder.recording());
  Result<CameraPath> path = recorder.finish();
  ASSERT_TRUE(path) << path.error().message;
  EXPECT_FALSE(recorder.recording());
  const auto& keys = path->keyframes();
  EXPECT_EQ(keys.size(), 12u);  // 0, 0.25, ..., 2.5 and the last camera, at 2.67
  EXPECT_DOUBLE_EQ(keys.front().timeS, 0.0);
  EXPECT_NEAR(keys.back().timeS, 160.0 / 60.0, 1e-9);
  for (std::size_t i = 1; i < keys.size(); ++i) {
    if (i + 1 < keys.size()) {
      EXPECT_NEAR(keys[i].timeS - keys[i - 1].timeS, 0.25, 1e-9);
    }
  }
}

TEST(PathRecorder, TheSavedPathReplaysTheFlight) {
  PathRecorder recorder(0.25);
  recorder.start(0.0);
  for (int frame = 0; frame <= 300; ++frame) recorder.add(frame / 60.0, flight(frame / 60.0));
  Result<CameraPath> path = recorder.finish();
  ASSERT_TRUE(path);
  const auto file = test::testOutputDir() / "recorded-path.json";
  ASSERT_TRUE(saveCameraPath(path.value(), file));
  Result<CameraPath> loaded = loadCameraPath(file);
  ASSERT_TRUE(loaded) << loaded.error().message;
  // Keyframes every 0.25 s of a uniform flight: the spline reproduces it exactly, except in
  // the first and last interval where its end condition eases in and out (under 2% of the
  // 25 m flown per interval).
  for (double t = 0.0; t <= 5.0; t += 0.05) {
    const Camera replayed = loaded->at(t), flown = flight(t);
    const bool endInterval = t < 0.25 || t > 4.75;
    const double tolerance = endInterval ? 0.5 : 1e-6;
    EXPECT_NEAR(glm::distance(replayed.position, flown.position), 0.0, 4 * tolerance) << t;
    EXPECT_NEAR(replayed.yawDeg, flown.yawDeg, 0.4 * tolerance) << "t=" << t;
    EXPECT_NEAR(replayed.pitchDeg, flown.pitchDeg, 1e-9);
  }
}

// On the globe: a flight along the equator across the antimeridian, descending, recorded as
// lat/lon keyframes that the globe path reader gives back bit for bit.
TEST(PathRecorder, AGlobeFlightSavesAsLatLonKeyframesThatReadBack) {
  GeoPathRecorder recorder(0.5);
  recorder.start(10.0);
  const auto camera = [](double t) {
    return GeoCamera{0.1 * t, 179.0 + 0.4 * t, 20000.0 / (1.0 + t), 90.0, -20.0 + t, 55.0};
  };
  for (int frame = 0; frame <= 240; ++frame) recorder.add(10.0 + frame / 60.0, camera(frame / 60.0));
  EXPECT_EQ(recorder.keyframeCount(), 9u);  // 0, 0.5, ... 4 s
  Result<GeoCameraPath> path = recorder.finish();
  ASSERT_TRUE(path) << path.error().message;
  ASSERT_EQ(path->keyframes().size(), 9u);
  const auto file = test::testOutputDir() / "recorded-globe-path.json";
  ASSERT_TRUE(saveGeoCameraPath(path.value(), file));
  Result<GeoCameraPath> loaded =
      makeGeoCameraPath(file.string(), [](double, double) { return 0.0; }, {});
  ASSERT_TRUE(loaded) << loaded.error().message;
  ASSERT_EQ(loaded->keyframes().size(), 9u);
  for (std::size_t i = 0; i < 9; ++i) {
    const GeoCameraKeyframe& a = path->keyframes()[i];
    const GeoCameraKeyframe& b = loaded->keyframes()[i];
    EXPECT_EQ(a.timeS, b.timeS);
    EXPECT_EQ(a.camera.latDeg, b.camera.latDeg);
    EXPECT_EQ(a.camera.lonDeg, b.camera.lonDeg);
    EXPECT_EQ(a.camera.altitudeM, b.camera.altitudeM);
    EXPECT_EQ(a.camera.headingDeg, b.camera.headingDeg);
    EXPECT_EQ(a.camera.pitchDeg, b.camera.pitchDeg);
    EXPECT_EQ(a.camera.fovYDeg, b.camera.fovYDeg);
  }
  EXPECT_DOUBLE_EQ(loaded->keyframes().back().camera.lonDeg, 180.6);  // not wrapped on the way
}

TEST(PathRecorder, ATooShortRecordingIsAnErrorAndANewStartForgetsTheOld) {
  PathRecorder recorder;
  recorder.start(5.0);
  recorder.add(5.0, flight(0.0));
  recorder.add(5.0, flight(0.0));
  Result<CameraPath> path = recorder.finish();
  ASSERT_FALSE(path);
  EXPECT_NE(path.error().message.find("too short"), std::string::npos);

  recorder.start(0.0);
  recorder.add(0.0, flight(0.0));
  recorder.add(10.0, flight(10.0));
  recorder.start(20.0);  // starts over
  recorder.add(20.0, flight(0.0));
  recorder.add(21.0, flight(1.0));
  path = recorder.finish();
  ASSERT_TRUE(path);
  EXPECT_DOUBLE_EQ(path->durationS(), 1.0);
}

TEST(FrameHistory, KeepsTheLastFramesInOrderAndFillsInLateGpuTimes) {
  FrameHistory history(4);
  EXPECT_EQ(history.medianGpuMs(), -1.0);
  for (int i = 1; i <= 6; ++i) history.add(double(i), -1.0);
  EXPECT_EQ(history.cpuSeries(), (std::vector<float>{3, 4, 5, 6}));
  history.setGpuMs(0, 60.0);  // the last frame
  history.setGpuMs(2, 40.0);
  history.setGpuMs(9, 1.0);  // long gone: ignored
  EXPECT_EQ(history.gpuSeries(), (std::vector<float>{-1, 40, -1, 60}));
  EXPECT_DOUBLE_EQ(history.medianCpuMs(), 5.0);   // upper median of 3, 4, 5, 6
  EXPECT_DOUBLE_EQ(history.medianGpuMs(), 60.0);  // of the known 40 and 60
  EXPECT_EQ(history.medianIntervalMs(), -1.0);    // no wall-clock times given
  history.add(7.0, -1.0, 16.0);
  history.add(8.0, -1.0, 20.0);
  EXPECT_DOUBLE_EQ(history.medianIntervalMs(), 20.0);

  FrameHistory partial(10);
  partial.add(1.0, -1.0);
  partial.add(2.0, -1.0);
  partial.setGpuMs(1, 7.0);
  EXPECT_EQ(partial.gpuSeries(), (std::vector<float>{7, -1}));
}

}  // namespace
}  // namespace tellus
