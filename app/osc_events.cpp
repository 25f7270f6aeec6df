#include "osc_events.h"

#include <lo/lo.h>

#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "cli_checks.h"
#include "untrusted.h"

namespace gb {

struct OscSender::Address {
  lo_address handle = nullptr;
  ~Address() {
    if (handle) lo_address_free(handle);
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
  address_->handle = lo_address_new(host.c_str(), port.c_str());
  if (!address_->handle) throw std::invalid_argument(named + " cannot be used");
}

OscSender::~OscSender() = default;

bool OscSender::event(const std::string& name, double time) {
  if (lo_send(address_->handle, "/giantbubble/event", "sd", name.c_str(), time) >= 0) return true;
  lastError_ = lo_address_errstr(address_->handle);
  return false;
}

bool OscSender::bubble(double time, const Vec3& centre, double area, double volume, double solution) {
  if (lo_send(address_->handle, "/giantbubble/bubble", "dffffff", time, centre.x(), centre.y(), centre.z(),
              static_cast<float>(area), static_cast<float>(volume), static_cast<float>(solution)) >= 0)
    return true;
  lastError_ = lo_address_errstr(address_->handle);
  return false;
}

bool OscSender::cue(const std::string& name, const std::string& done, double time) {
  if (lo_send(address_->handle, "/giantbubble/cue", "ssd", name.c_str(), done.c_str(), time) >= 0) return true;
  lastError_ = lo_address_errstr(address_->handle);
  return false;
}

bool OscSender::joint(const std::string& name, int user, const std::array<float, 3>& p) {
  if (lo_send(address_->handle, "/joint", "sifff", name.c_str(), user, p[0], p[1], p[2]) >= 0) return true;
  lastError_ = lo_address_errstr(address_->handle);
  return false;
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

void ShowControl::check(bool sent) {
  if (!sent && !warned_) {
    std::fprintf(stderr, "warning: OSC messages are not getting through (%s); the show goes on\n",
                 sender_->lastError().c_str());
    warned_ = true;
  }
}

}  // namespace gb
