#include "app/outputs/osc_events.h"

#include <lo/lo.h>
#include <netdb.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <stdexcept>

#include "app/commands/cli_checks.h"
#include "capture/untrusted.h"

namespace gb {

// The target as a connected UDP socket: liblo builds each message, and the socket sends it. Connected, the socket
// hears the ICMP "port unreachable" a host answers when nothing listens on the port, so the next send fails with
// ECONNREFUSED and the show can say so (liblo's own sends go out unconnected and never learn it).
struct OscSender::Address {
  int socket = -1;
  std::string target;
  ~Address() {
    if (socket >= 0) close(socket);
  }
};

OscSender::OscSender(const std::string& target) : address_(std::make_unique<Address>()) {
  const std::string named = "OSC target '" + printable(target) + "'";
  const auto colon = target.rfind(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == target.size())
    throw std::invalid_argument(named + " is not HOST:PORT");
  const std::string host = target.substr(0, colon), port = target.substr(colon + 1);
  // Debian's liblo sends over IPv4 only: an IPv6 address would be taken and every message lost with a warning.
  if (host.front() == '[' || host.find(':') != std::string::npos)
    throw std::invalid_argument(named +
                                " is not HOST:PORT with an IPv4 address or a host name (IPv6 is not supported: "
                                "liblo sends over IPv4)");
  // A UDP port is 1 to 65535; liblo would take 99999 and send to 99999 mod 65536.
  if (!isPort(port)) throw std::invalid_argument(named + ": the port must be a number from 1 to 65535");
  addrinfo hints{};
  hints.ai_family = AF_INET;
  hints.ai_socktype = SOCK_DGRAM;
  addrinfo* found = nullptr;
  if (const int error = getaddrinfo(host.c_str(), port.c_str(), &hints, &found); error != 0 || !found)
    throw std::invalid_argument(named + ": " + (error != 0 ? gai_strerror(error) : "no address"));
  address_->socket = ::socket(found->ai_family, found->ai_socktype, found->ai_protocol);
  const bool connected =
      address_->socket >= 0 && connect(address_->socket, found->ai_addr, found->ai_addrlen) == 0;  // sends nothing
  const int error = errno;
  freeaddrinfo(found);
  if (!connected) throw std::invalid_argument(named + " cannot be used: " + std::strerror(error));
  address_->target = printable(target);
}

OscSender::~OscSender() = default;

bool OscSender::send(const char* path, lo_message message) {
  size_t size = 0;
  void* bytes = lo_message_serialise(message, path, nullptr, &size);
  const bool sent = bytes && ::send(address_->socket, bytes, size, MSG_DONTWAIT) == static_cast<ssize_t>(size);
  const int error = errno;
  std::free(bytes);
  lo_message_free(message);
  if (sent) return true;
  lastError_ = error == ECONNREFUSED ? "nothing listens at " + address_->target + ": the port refused them"
                                     : address_->target + ": " + std::strerror(error);
  return false;
}

bool OscSender::event(const std::string& name, double time) {
  lo_message m = lo_message_new();
  lo_message_add(m, "sd", name.c_str(), time);
  return send("/giantbubble/event", m);
}

bool OscSender::bubble(double time, const Vec3& centre, double area, double volume, double solution) {
  lo_message m = lo_message_new();
  lo_message_add(m, "dffffff", time, centre.x(), centre.y(), centre.z(), static_cast<float>(area),
                 static_cast<float>(volume), static_cast<float>(solution));
  return send("/giantbubble/bubble", m);
}

bool OscSender::touch(double time, const Vec3& position, float approachSpeed) {
  lo_message m = lo_message_new();
  lo_message_add(m, "dffff", time, position.x(), position.y(), position.z(), approachSpeed);
  return send("/giantbubble/touch", m);
}

bool OscSender::cue(const std::string& name, const std::string& done, double time) {
  lo_message m = lo_message_new();
  lo_message_add(m, "ssd", name.c_str(), done.c_str(), time);
  return send("/giantbubble/cue", m);
}

bool OscSender::joint(const std::string& name, int user, const std::array<float, 3>& p) {
  lo_message m = lo_message_new();
  lo_message_add(m, "sifff", name.c_str(), user, p[0], p[1], p[2]);
  return send("/joint", m);
}

bool OscSender::performer(const std::string& state, const std::string& detail) {
  lo_message m = lo_message_new();
  lo_message_add(m, "ss", state.c_str(), detail.c_str());
  return send("/giantbubble/performer", m);
}

std::array<float, 3> oscCeletonPosition(const Vec3d& camera) {
  // OSCeleton maps a tracker's millimetres so: x over 2560 mm, y over 1920 mm (down), z 7.8125 per 10 m.
  return {static_cast<float>(0.5 + 1000.0 * camera.x() / 2560.0),
          static_cast<float>(0.5 - 1000.0 * camera.y() / 1920.0),
          static_cast<float>(1000.0 * camera.z() * 7.8125 / 10000.0)};
}

ShowControl::ShowControl(const std::string& target) {
  if (!target.empty()) sender_ = std::make_unique<OscSender>(target);
}

void ShowControl::frame(const Simulation& sim, const FrameStats& stats, const std::string& events) {
  if (!sender_) return;
  std::istringstream words(events);
  bool ok = true;
  for (std::string event; words >> event;) ok = sender_->event(event, stats.time) && ok;
  if (events.find("burst_by_touch") != std::string::npos && sim.lastTouch())
    ok = sender_->touch(stats.time, sim.lastTouch()->position, sim.lastTouch()->approachSpeed) && ok;
  ok = sender_->bubble(stats.time, centroid(sim.filmPositionsOnly().state), stats.area, stats.volume, stats.solution) &&
       ok;
  check(ok);
}

void ShowControl::cue(const std::string& name, const std::string& done, double time) {
  if (sender_) check(sender_->cue(name, done, time));
}

void ShowControl::hands(const Vec3d& left, const Vec3d& right) {
  if (!sender_) return;
  bool ok = true;
  if (left.allFinite()) ok = sender_->joint("l_hand", 1, oscCeletonPosition(left)) && ok;
  if (right.allFinite()) ok = sender_->joint("r_hand", 1, oscCeletonPosition(right)) && ok;
  check(ok);
}

void ShowControl::performer(const std::string& state, const std::string& detail) {
  if (sender_) check(sender_->performer(state, detail));
}

void ShowControl::check(bool sent) {
  if (!sent && !warned_) {
    std::fprintf(stderr, "warning: OSC messages are not getting through (%s); the show goes on\n",
                 sender_->lastError().c_str());
    warned_ = true;
  }
}

}  // namespace gb
