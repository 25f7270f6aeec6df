#include "app/show/osc_cues.h"

#include <lo/lo.h>

#include <cmath>
#include <stdexcept>
#include <utility>

#include "capture/untrusted.h"

namespace gb {

namespace {

constexpr std::pair<const char*, CueAction> kCues[] = {
    {"dip", CueAction::Dip},
    {"burst", CueAction::Burst},
    {"reset", CueAction::Reset},
    {"pause", CueAction::Pause},
    {"colouring", CueAction::Colouring},
    {"camera", CueAction::Camera},
    {"fullscreen", CueAction::Fullscreen},
    {"performer_view", CueAction::PerformerView},
    {"operator", CueAction::Operator},
    {"quit", CueAction::Quit},
};
constexpr std::string_view kPrefix = "/giantbubble/";

// liblo's error handler has no user data: the receiver being polled (or made) on this thread, and the last error
// while none is.
thread_local OscCueReceiver* tPolling = nullptr;
thread_local std::string tLastError;

}  // namespace

const char* cueName(CueAction action) {
  for (const auto& [name, a] : kCues)
    if (a == action) return name;
  return "?";
}

struct OscCueReceiver::Server {
  lo_server handle = nullptr;
  ~Server() {
    if (handle) lo_server_free(handle);
  }
};

// liblo's callbacks, with the receiver's private counters.
struct OscCueDispatch {
  static void onError(int number, const char* message, const char* where) {
    std::string text = std::string(message ? message : "error") + " (" + std::to_string(number) + ")";
    if (where) text += " at " + printable(where, 80);
    if (tPolling)
      tPolling->ignore(false, "a packet that is not an OSC message: " + text);
    else
      tLastError = text;
  }

  static int onMessage(const char* path, const char* types, lo_arg** argv, int argc, lo_message message, void* data) {
    auto& r = *static_cast<OscCueReceiver*>(data);
    const std::string_view address(path);
    const CueAction* action = nullptr;
    if (address.starts_with(kPrefix))
      for (const auto& [name, a] : kCues)
        if (address.substr(kPrefix.size()) == name) action = &a;
    if (!action && r.other_ && r.other_(path, message)) {
      ++r.taken_;
      return 0;
    }
    if (!action) {
      r.ignore(true, "unknown address " + printable(std::string(address), 80));
      return 0;
    }
    double value = 1.0;
    bool number = argc == 0;
    if (argc == 1) {
      number = true;
      switch (types[0]) {
        case LO_INT32:
          value = argv[0]->i;
          break;
        case LO_INT64:
          value = static_cast<double>(argv[0]->h);
          break;
        case LO_FLOAT:
          value = argv[0]->f;
          break;
        case LO_DOUBLE:
          value = argv[0]->d;
          break;
        case LO_TRUE:
          break;
        case LO_FALSE:
          value = 0.0;
          break;
        default:
          number = false;
      }
    }
    if (!number) {
      r.ignore(false, std::string(path) + " with arguments '" + printable(types, 20) +
                          "': a cue takes no argument or one number");
      return 0;
    }
    if (!std::isfinite(value)) {  // NaN would pause (NaN != 0) and resume at once on another reading
      r.ignore(false, std::string(path) + " with " + std::to_string(value) + ": a cue's number is finite");
      return 0;
    }
    ++r.taken_;
    if (*action == CueAction::Pause)
      r.arrived_.push_back({*action, argc == 0 ? -1 : (value != 0.0 ? 1 : 0)});
    else if (value != 0.0)  // 0: a push button let go of
      r.arrived_.push_back({*action, -1});
    return 0;
  }
};

OscCueReceiver::OscCueReceiver(int port) : server_(std::make_unique<Server>()) {
  if (port < 0 || port > 65535)
    throw std::runtime_error("--osc-in " + std::to_string(port) + ": the port must be a number from 1 to 65535");
  tLastError.clear();
  const std::string name = std::to_string(port);
  server_->handle = lo_server_new_with_proto(port == 0 ? nullptr : name.c_str(), LO_UDP, OscCueDispatch::onError);
  if (!server_->handle)
    throw std::runtime_error("--osc-in " + std::to_string(port) + ": cannot listen on UDP port " +
                             std::to_string(port) + (tLastError.empty() ? "" : " (" + tLastError + ")") +
                             ": is another program listening there?");
  lo_server_add_method(server_->handle, nullptr, nullptr, OscCueDispatch::onMessage, this);
}

OscCueReceiver::~OscCueReceiver() = default;

int OscCueReceiver::port() const { return lo_server_get_port(server_->handle); }

std::vector<Cue> OscCueReceiver::poll() {
  tPolling = this;
  for (int k = 0; k < kMostPerPoll; ++k)
    if (lo_server_recv_noblock(server_->handle, 0) <= 0) break;
  tPolling = nullptr;
  return std::exchange(arrived_, {});
}

std::vector<std::string> OscCueReceiver::takeMessages() { return std::exchange(messages_, {}); }

void OscCueReceiver::ignore(bool unknown, const std::string& why) {
  ++(unknown ? unknown_ : malformed_);
  if (unknown_ + malformed_ <= kMostReported)
    messages_.push_back("osc in: " + why + " (ignored" +
                        (unknown_ + malformed_ == kMostReported ? "; further ones are only counted)" : ")"));
}

}  // namespace gb
