// The parts of `render --frames-out` that need no device: frame ranges, `#` names, the image
// writer's threads and failures, --progress words, device UUIDs and --device's reading.
#include <atomic>
#include <chrono>
#include <filesystem>
#include <thread>

#include <gtest/gtest.h>

#include "app/device_option.h"
#include "app/frame_range.h"
#include "app/image_writer.h"
#include "app/progress.h"
#include "app/sequence.h"
#include "core/image_io.h"
#include "rhi/context.h"
#include "tests/support/test_dirs.h"

namespace rayster::app {
namespace {

TEST(FrameRange, ParsesFirstLastAndStep) {
  auto r = parseFrameRange("10:12");
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->first, 10);
  EXPECT_EQ(r->last, 12);
  EXPECT_EQ(r->count(), 3u);
  auto s = parseFrameRange("0:10:4");
  ASSERT_TRUE(s.ok());
  EXPECT_EQ(s->count(), 3u);  // 0, 4, 8
  EXPECT_EQ(s->at(2), 8);
  EXPECT_EQ(parseFrameRange("7:7").value().count(), 1u);
  for (const char* bad : {"5:2", "", "3", "1:2:3:4", "-1:3", "a:b", "0:3:0", "0:99999999", "1 :2", "0:+3"}) {
    auto e = parseFrameRange(bad);
    ASSERT_FALSE(e.ok()) << bad;
    EXPECT_EQ(e.error().code, ExitCode::BadArguments) << bad;
  }
}

TEST(FrameRange, HashRunsBecomeTheZeroPaddedNumber) {
  EXPECT_EQ(framePath("out/shot_####.png", 12), "out/shot_0012.png");
  EXPECT_EQ(framePath("out/shot_#.png", 123), "out/shot_123.png");  // longer numbers in full
  EXPECT_EQ(framePath("a_##_b_###.exr", 7), "a_07_b_007.exr");
  EXPECT_EQ(framePath("dir#1/f_##.png", 3), "dir#1/f_03.png");  // folders keep their #
  EXPECT_TRUE(hasFrameNumber("out/f_#.png"));
  EXPECT_FALSE(hasFrameNumber("out#/f.png"));
}

TEST(FrameRange, AnOutputFramesRunEndsOnIt) {
  render::RenderSettings s;
  s.frames = 4;
  EXPECT_EQ(outputFrameSettings(s, 10).frameOffset, 7);  // frames 7, 8, 9, 10
  EXPECT_EQ(outputFrameSettings(s, 0).frameOffset, -3);  // frames before 0 show frame 0
  s.mode = render::Mode::PathTrace;                      // every sample at the frame itself
  EXPECT_EQ(outputFrameSettings(s, 10).frameOffset, 10);
}

TEST(ImageWriter, WritesOnWorkerThreadsWithABoundedQueue) {
  const auto dir = test::testDir();
  std::atomic<int> running{0}, most{0};
  const auto caller = std::this_thread::get_id();
  std::atomic<bool> onCaller{false};
  {
    ImageWriter writer(2, 2);
    for (int i = 0; i < 8; ++i)
      writer.push([&, i] {
        if (std::this_thread::get_id() == caller) onCaller = true;
        const int now = ++running;
        most = std::max(most.load(), now);
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        Image8 img;
        img.width = img.height = 2;
        img.rgba.assign(16, uint8_t(i));
        --running;
        return writePng(dir / ("f" + std::to_string(i) + ".png"), img);
      });
    ASSERT_TRUE(writer.finish().ok());
    EXPECT_EQ(writer.jobsDone(), 8u);
    EXPECT_GT(writer.encodeSeconds(), 0.1);  // 8 × 20 ms on the workers
    EXPECT_GT(writer.waitSeconds(), 0.02);   // the queue of 2 made the caller wait
  }
  EXPECT_FALSE(onCaller.load());
  EXPECT_LE(most.load(), 2);
  for (int i = 0; i < 8; ++i) EXPECT_TRUE(std::filesystem::exists(dir / ("f" + std::to_string(i) + ".png"))) << i;
}

TEST(ImageWriter, TheFirstFailureIsKeptAndLaterFramesAreDropped) {
  const auto dir = test::testDir();
  std::filesystem::create_directories(dir / "taken.png");  // a folder where the file should go
  ImageWriter writer(1, 4);
  Image8 img;
  img.width = img.height = 1;
  img.rgba.assign(4, 0);
  writer.push([&] { return writePng(dir / "taken.png", img); });
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  ASSERT_TRUE(writer.failure().has_value());
  writer.push([&] { return writePng(dir / "after.png", img); });
  Status done = writer.finish();
  ASSERT_FALSE(done.ok());
  EXPECT_EQ(done.error().code, ExitCode::OutputFailed);
  EXPECT_NE(done.error().message.find("taken.png"), std::string::npos) << done.error().message;
  EXPECT_FALSE(std::filesystem::exists(dir / "after.png"));
  for (const auto& e : std::filesystem::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
}

TEST(Progress, WordsAndDurations) {
  EXPECT_EQ(parseProgress("auto", true).value(), ProgressStyle::Bar);
  EXPECT_EQ(parseProgress("auto", false).value(), ProgressStyle::Lines);
  EXPECT_EQ(parseProgress("bar", false).value(), ProgressStyle::Bar);
  EXPECT_EQ(parseProgress("lines", true).value(), ProgressStyle::Lines);
  EXPECT_EQ(parseProgress("off", true).value(), ProgressStyle::Off);
  EXPECT_FALSE(parseProgress("on", true).ok());
  EXPECT_EQ(formatDuration(42.4), "42 s");
  EXPECT_EQ(formatDuration(187), "3:07");
  EXPECT_EQ(formatDuration(3723), "1:02:03");
}

TEST(DeviceOption, IndexUuidOrName) {
  const rhi::DeviceUuid u = {0x6d, 0x65, 0x73, 0x61, 0x32, 0x35, 0x2e, 0x30,
                             0x2e, 0x37, 0x2d, 0x32, 0x7e, 0x62, 0x70, 0x00};
  EXPECT_EQ(rhi::formatDeviceUuid(u), "6d657361-3235-2e30-2e37-2d327e627000");
  EXPECT_EQ(rhi::parseDeviceUuid("6D657361-3235-2E30-2E37-2D327E627000"), u);
  EXPECT_EQ(rhi::parseDeviceUuid("6d6573613235"
                                 "2e302e372d327e627000"),
            u);
  EXPECT_FALSE(rhi::parseDeviceUuid("6d657361-3235-2e30-2e37-2d327e6270").has_value());
  EXPECT_FALSE(rhi::parseDeviceUuid("6d65736-13235-2e30-2e37-2d327e627000").has_value());
  EXPECT_EQ(deviceSelector("3").index, 3u);
  EXPECT_EQ(deviceSelector("6d657361-3235-2e30-2e37-2d327e627000").uuid, u);
  const rhi::DeviceSelector name = deviceSelector("H200");
  EXPECT_FALSE(name.index || name.uuid);
  EXPECT_EQ(name.nameContains, "H200");
  EXPECT_TRUE(deviceSelector("").nameContains.empty());
}

}  // namespace
}  // namespace rayster::app
