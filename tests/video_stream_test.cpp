// Video out (app/show/video_stream.h): ffmpeg's arguments for each kind of address, a bad address named, and a stream
// that never holds up the show, whether nobody receives it or ffmpeg cannot reach its receiver.
#include "app/show/video_stream.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <thread>

#include "app/outputs/render_output.h"

namespace gb {
namespace {

bool has(const std::vector<std::string>& args, const std::string& a, const std::string& b) {
  for (size_t k = 0; k + 1 < args.size(); ++k)
    if (args[k] == a && args[k + 1] == b) return true;
  return false;
}

TEST(VideoStream, EachAddressGetsItsContainer) {
  const auto udp = streamArguments("udp://127.0.0.1:5000", 960, 540);
  EXPECT_TRUE(has(udp, "-f", "mpegts"));
  EXPECT_TRUE(has(udp, "-s", "960x540"));
  EXPECT_TRUE(has(udp, "-pix_fmt", "rgba"));
  EXPECT_TRUE(has(udp, "-use_wallclock_as_timestamps", "1"));  // the presented frame rate
  EXPECT_EQ(udp.back(), "udp://127.0.0.1:5000?pkt_size=1316");
  EXPECT_EQ(streamArguments("udp://239.0.0.1:5000?ttl=2", 16, 16).back(), "udp://239.0.0.1:5000?ttl=2&pkt_size=1316");
  EXPECT_TRUE(has(streamArguments("srt://host:9000", 16, 16), "-f", "mpegts"));
  EXPECT_TRUE(has(streamArguments("rtmp://host/live/key", 16, 16), "-f", "flv"));
  const auto v4l2 = streamArguments("/dev/video7", 16, 16);
  EXPECT_TRUE(has(v4l2, "-f", "v4l2"));
  EXPECT_TRUE(has(v4l2, "-c:v", "rawvideo"));
  EXPECT_EQ(v4l2.back(), "/dev/video7");
}

TEST(VideoStream, AnAddressItCannotStreamToIsNamed) {
  for (const char* bad : {"", "stream.ts", "http://host/x", "-y", "file:/tmp/x", "udp://host:1\nrm"}) {
    try {
      (void)streamArguments(bad, 16, 16);
      ADD_FAILURE() << "'" << bad << "' was taken";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("not an address to stream to: give udp://HOST:PORT"), std::string::npos)
          << e.what();
    }
  }
}

// Offers `count` frames at `fps` and returns the longest an offer took (s).
double offer(VideoStream& stream, int count, double fps) {
  const std::vector<uint8_t> frame(4ull * stream.width() * stream.height(), 128);
  double longest = 0;
  for (int k = 0; k < count; ++k) {
    const auto start = std::chrono::steady_clock::now();
    stream.offer(frame);
    longest = std::max(longest, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    std::this_thread::sleep_for(std::chrono::duration<double>(1.0 / fps));
  }
  return longest;
}

TEST(VideoStream, NobodyReceivingNeverHoldsUpTheShow) {
  if (!ffmpegAvailable()) GTEST_SKIP() << "ffmpeg is not installed";
  // UDP to a port nobody listens on: ffmpeg sends into the void and the frames flow.
  double closing = 0;
  {
    // At the show's priority: below it (live's stream) ffmpeg waits for an idle core, which a machine running other
    // tests beside this one may not leave it for many seconds.
    VideoStream stream("udp://127.0.0.1:9", 320, 240, StreamPriority::Normal);
    // An offer copies a frame and wakes the sender: well under a millisecond; 20 ms leaves room for a loaded machine
    // (a frame at 50 frames/s).
    EXPECT_LT(offer(stream, 50, 25.0), 0.02);
    // The sender may still hold the frame it writes and the one waiting while ffmpeg starts: 10 s is far more than
    // ffmpeg needs for 50 frames of 320x240 on a loaded machine.
    const auto settled = [&] { return stream.sent() > 0 && stream.sent() + stream.dropped() == 50; };
    for (int k = 0; k < 100 && !settled(); ++k) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    EXPECT_GT(stream.sent(), 0);
    EXPECT_EQ(stream.sent() + stream.dropped(), 50) << "every frame offered is sent or dropped";
    closing = std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  }
  // Closing waits for ffmpeg at most kCloseSeconds, and then some for the kill.
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count() - closing,
            VideoStream::kCloseSeconds + 1.0);
}

TEST(VideoStream, AReceiverThatCannotBeReachedIsSaidOnceAndTheShowGoesOn) {
  if (!ffmpegAvailable()) GTEST_SKIP() << "ffmpeg is not installed";
  // RTMP to a port where nothing listens: ffmpeg fails to connect and ends.
  VideoStream stream("rtmp://127.0.0.1:9/live/show", 64, 48, StreamPriority::Normal);  // as above
  std::vector<std::string> said;
  double longest = 0;
  for (int k = 0; k < 40 && said.empty(); ++k) {
    longest = std::max(longest, offer(stream, 5, 50.0));
    for (const std::string& m : stream.takeMessages()) said.push_back(m);
  }
  ASSERT_EQ(said.size(), 1u) << "the end of ffmpeg is said once";
  EXPECT_NE(said[0].find("stream: ffmpeg sending to rtmp://127.0.0.1:9/live/show ended"), std::string::npos) << said[0];
  EXPECT_NE(said[0].find("started again every 5 s"), std::string::npos) << said[0];
  EXPECT_LT(longest, 0.02);  // as above: an offer never waits for ffmpeg
}

}  // namespace
}  // namespace gb
