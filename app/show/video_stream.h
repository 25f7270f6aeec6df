#pragma once
// Video out (giantbubble live --stream URL): the show's picture sent to show software (OBS, TouchDesigner, Resolume,
// a media server) through ffmpeg, started without a shell (child_process.h) as the MP4 of a run is:
//   udp://HOST:PORT, srt://HOST:PORT, tcp://HOST:PORT   H.264 in MPEG-TS
//   rtmp://HOST/APP/KEY, rtmps://...                   H.264 in FLV
//   /dev/videoN                                        raw YUV 4:2:0 into a v4l2 loopback device
// Each presented frame is offered with its wall-clock time (ffmpeg stamps it on arrival), so the stream runs at the
// presented frame rate. The show never waits for the stream: a sender thread feeds ffmpeg, and a frame offered while
// it is still busy with the one before replaces the one waiting, the older dropped and counted. ffmpeg runs only on
// what the show leaves idle (SCHED_IDLE), so on a loaded machine the stream drops frames rather than the show. When
// ffmpeg ends (no receiver at an RTMP or SRT address, a network error) the show goes on, says so once, and ffmpeg
// is started again every kRetrySeconds.

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace gb {

// ffmpeg's arguments for a stream of width x height RGBA frames to `url`. Throws std::invalid_argument naming the
// URL and the forms taken when it is none of them.
std::vector<std::string> streamArguments(const std::string& url, int width, int height);

// How ffmpeg is scheduled beside the show.
enum class StreamPriority {
  BelowTheShow,  // SCHED_IDLE (nice 19 where refused): it runs on what the show leaves of the cores, so the stream
                 // drops frames before the show slows (live's stream)
  Normal,        // as the show: frames flow whatever else keeps the cores busy (the tests of the sender on a
                 // machine busy with other tests)
};

class VideoStream {
 public:
  static constexpr double kRetrySeconds = 5.0;
  static constexpr double kCloseSeconds = 2.0;  // ffmpeg's time to finish when the show ends, then it is killed

  // Checks the URL (streamArguments) and that ffmpeg is installed, then starts it. Throws std::runtime_error (or
  // std::invalid_argument for the URL) naming the problem.
  VideoStream(const std::string& url, int width, int height, StreamPriority priority = StreamPriority::BelowTheShow);
  ~VideoStream();  // ends the stream: ffmpeg gets kCloseSeconds to finish, and is killed after that
  VideoStream(const VideoStream&) = delete;  // owns the sender thread and ffmpeg
  VideoStream& operator=(const VideoStream&) = delete;

  // Offers a frame (width x height RGBA, rows from the top). Never waits for ffmpeg.
  void offer(const std::vector<uint8_t>& rgba);
  [[nodiscard]] long sent() const { return sent_; }
  [[nodiscard]] long dropped() const { return dropped_; }
  [[nodiscard]] int width() const { return width_; }
  [[nodiscard]] int height() const { return height_; }
  // "stream: ffmpeg ended (exit status 1); it is started again every 5 s", at most once per failure, since the
  // last call.
  std::vector<std::string> takeMessages();

 private:
  std::string url_;
  std::vector<std::string> arguments_;
  int width_, height_;
  size_t frameBytes_;
  StreamPriority priority_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::vector<uint8_t> waiting_;  // the frame offered and not yet taken by the sender
  bool hasWaiting_ = false;
  bool stop_ = false;
  std::atomic<long> sent_{0}, dropped_{0};
  std::atomic<bool> writing_{false};  // the sender is writing a frame to ffmpeg
  int pid_ = -1;                      // ffmpeg's while it runs, under mutex_ (the destructor may kill it)
  std::vector<std::string> messages_;
  std::thread sender_;
  void send(int pipe);  // the sender thread, from ffmpeg's stdin `pipe`
  int start();          // starts ffmpeg; the write end of its stdin, or -1 (said why)
  // Closes the pipe and reaps ffmpeg, killed after kCloseSeconds; says why it ended unless `closing` and it ended
  // well.
  void finish(int pipe, bool closing);
  void say(const std::string& message);
};

}  // namespace gb
