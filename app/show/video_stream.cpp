#include "app/show/video_stream.h"

#include <fcntl.h>
#include <sched.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <stdexcept>
#include <utility>

#include "app/commands/cli_checks.h"
#include "app/outputs/child_process.h"
#include "app/outputs/render_output.h"
#include "capture/output_file.h"
#include "capture/untrusted.h"

namespace gb {

namespace {

using Clock = std::chrono::steady_clock;

bool startsWith(const std::string& text, const char* prefix) { return text.rfind(prefix, 0) == 0; }

std::string exitStatus(int status) {
  if (WIFEXITED(status)) return "exit status " + std::to_string(WEXITSTATUS(status));
  if (WIFSIGNALED(status)) return "killed by signal " + std::to_string(WTERMSIG(status));
  return "status " + std::to_string(status);
}

}  // namespace

std::vector<std::string> streamArguments(const std::string& url, int width, int height) {
  std::string format;
  if (startsWith(url, "udp://") || startsWith(url, "srt://") || startsWith(url, "tcp://"))
    format = "mpegts";
  else if (startsWith(url, "rtmp://") || startsWith(url, "rtmps://"))
    format = "flv";
  else if (startsWith(url, "/dev/video"))
    format = "v4l2";
  if (format.empty() || url.find_first_of(std::string("\0\n\r\t", 4)) != std::string::npos)
    throw std::invalid_argument("--stream '" + printable(url) +
                                "': not an address to stream to: give udp://HOST:PORT, srt://HOST:PORT or "
                                "tcp://HOST:PORT (MPEG-TS), rtmp://HOST/APP/KEY (FLV) or a v4l2 loopback device "
                                "/dev/videoN");
  if (format == "mpegts") {  // HOST:PORT: a port that is no port would be taken and every packet lost
    const size_t start = url.find("://") + 3;
    const std::string address = url.substr(start, url.find_first_of("/?", start) - start);
    const size_t colon = address.rfind(':');
    if (colon == std::string::npos || !isPort(std::string_view(address).substr(colon + 1)))
      throw std::invalid_argument("--stream '" + printable(url) + "': the port must be a number from 1 to 65535 (" +
                                  url.substr(0, start) + "HOST:PORT)");
  }
  std::vector<std::string> args = {
      "ffmpeg", "-loglevel", "error", "-nostdin",
      // Raw frames on stdin, each stamped with the wall clock as it arrives: the stream keeps the show's pace.
      "-f", "rawvideo", "-pix_fmt", "rgba", "-s", std::to_string(width) + "x" + std::to_string(height),
      "-use_wallclock_as_timestamps", "1", "-i", "pipe:0",
      // yuv420p needs even sizes: ffmpeg pads by one pixel where they are odd.
      "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-pix_fmt", "yuv420p", "-fps_mode", "passthrough"};
  if (format == "v4l2") {
    args.insert(args.end(), {"-c:v", "rawvideo", "-f", "v4l2", url});
    return args;
  }
  // H.264 at the fastest preset without frame reordering (the least delay), a key frame every second so that a
  // receiver that joins late has a picture within a second.
  args.insert(args.end(), {"-c:v", "libx264", "-preset", "ultrafast", "-tune", "zerolatency", "-force_key_frames",
                           "expr:gte(t,n_forced*1)", "-f", format,
                           // UDP: packets of seven TS packets (1316 bytes), within any network's MTU.
                           format == "mpegts" && startsWith(url, "udp://")
                               ? url + (url.find('?') == std::string::npos ? "?" : "&") + "pkt_size=1316"
                               : url});
  return args;
}

VideoStream::VideoStream(const std::string& url, int width, int height, StreamPriority priority)
    : url_(url),
      arguments_(streamArguments(url, width, height)),
      width_(width),
      height_(height),
      frameBytes_(4ull * static_cast<size_t>(width) * static_cast<size_t>(height)),
      priority_(priority) {
  if (!ffmpegAvailable())
    throw std::runtime_error("--stream needs ffmpeg, which is not installed (apt-get install ffmpeg)");
  std::signal(SIGPIPE, SIG_IGN);  // ffmpeg ending shows as a failed write, not as a signal that ends the show
  const int pipe = start();
  if (pipe < 0) throw std::runtime_error(messages_.empty() ? "--stream: cannot start ffmpeg" : messages_.back());
  messages_.clear();
  sender_ = std::thread([this, pipe] { send(pipe); });
}

VideoStream::~VideoStream() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  // A sender stuck writing to an ffmpeg that does not read (a receiver that takes nothing) is freed by ending
  // ffmpeg: the write then fails at once.
  const auto deadline = Clock::now() + std::chrono::duration<double>(kCloseSeconds);
  while (writing_ && Clock::now() < deadline) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  {
    std::lock_guard lock(mutex_);
    if (writing_ && pid_ > 0) kill(pid_, SIGKILL);
  }
  sender_.join();
}

void VideoStream::offer(const std::vector<uint8_t>& rgba) {
  if (rgba.size() != frameBytes_) throw std::logic_error("VideoStream::offer: a frame of the wrong size");
  {
    std::lock_guard lock(mutex_);
    if (hasWaiting_) ++dropped_;  // the sender is still busy: the older frame waiting is dropped for this one
    waiting_.assign(rgba.begin(), rgba.end());
    hasWaiting_ = true;
  }
  wake_.notify_one();
}

std::vector<std::string> VideoStream::takeMessages() {
  std::lock_guard lock(mutex_);
  return std::exchange(messages_, {});
}

void VideoStream::say(const std::string& message) {
  std::lock_guard lock(mutex_);
  messages_.push_back(message);
}

int VideoStream::start() {
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) {
    say("stream: cannot make a pipe to ffmpeg (" + std::string(std::strerror(errno)) + ")");
    return -1;
  }
  try {
    const pid_t pid = spawnWithStdin(arguments_, fds[0]);
    // Below the show: ffmpeg runs when the show leaves a core idle, so the stream drops frames first (its threads,
    // made later, inherit this). Where idle scheduling is refused, nice 19.
    const sched_param none{};
    if (priority_ == StreamPriority::BelowTheShow && sched_setscheduler(pid, SCHED_IDLE, &none) != 0)
      setpriority(PRIO_PROCESS, static_cast<id_t>(pid), 19);
    std::lock_guard lock(mutex_);
    pid_ = pid;
  } catch (const std::runtime_error& e) {
    ::close(fds[0]);
    ::close(fds[1]);
    say("stream: " + std::string(e.what()));
    return -1;
  }
  ::close(fds[0]);
  return fds[1];
}

void VideoStream::finish(int pipe, bool closing) {
  if (pipe >= 0) ::close(pipe);  // end of input: ffmpeg finishes the stream
  pid_t pid = -1;
  {
    std::lock_guard lock(mutex_);
    pid = std::exchange(pid_, -1);
  }
  if (pid <= 0) return;
  int status = 0;
  const auto deadline = Clock::now() + std::chrono::duration<double>(kCloseSeconds);
  pid_t reaped = 0;
  while ((reaped = waitpid(pid, &status, WNOHANG)) == 0 && Clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  if (reaped == 0) {  // still running (connecting to a receiver that does not answer): ended
    kill(pid, SIGKILL);
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (closing) return;
  }
  if (closing && WIFEXITED(status) && WEXITSTATUS(status) == 0) return;
  char retry[64];
  std::snprintf(retry, sizeof retry, "it is started again every %.0f s", kRetrySeconds);
  say("stream: ffmpeg sending to " + printable(url_) + " ended (" + exitStatus(status) + ")" +
      (closing ? "" : "; frames are dropped and " + std::string(retry)));
}

void VideoStream::send(int pipe) {
  std::vector<uint8_t> frame;
  auto retryAt = Clock::now();
  for (;;) {
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [&] { return stop_ || hasWaiting_; });
      if (stop_) break;
      frame.swap(waiting_);
      hasWaiting_ = false;
    }
    if (pipe < 0 && Clock::now() >= retryAt) {
      pipe = start();
      retryAt =
          Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(kRetrySeconds));
    }
    if (pipe < 0) {
      ++dropped_;
      continue;
    }
    writing_ = true;
    const bool written = writeAll(pipe, std::string_view(reinterpret_cast<const char*>(frame.data()), frame.size()));
    writing_ = false;
    if (written) {
      ++sent_;
      continue;
    }
    ++dropped_;
    std::unique_lock lock(mutex_);
    const bool closing = stop_;
    lock.unlock();
    finish(pipe, closing);
    pipe = -1;
    retryAt = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(kRetrySeconds));
  }
  finish(pipe, true);
}

}  // namespace gb
