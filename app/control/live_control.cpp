#include "app/control/live_control.h"

#include <lo/lo.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <string_view>

#include "app/commands/cli_checks.h"
#include "app/control/control_routes.h"
#include "app/control/control_server.h"
#include "app/control/param_catalog.h"
#include "app/show/osc_cues.h"
#include "capture/untrusted.h"
#include "scene/scene_file.h"
#include "simulation/simulation.h"

namespace gb {
namespace {

constexpr std::string_view kParamPrefix = "/giantbubble/param/";

// A message's one number (int, float, double, true, false), or false when it has other arguments.
bool oneNumber(lo_message message, double& value) {
  if (lo_message_get_argc(message) != 1) return false;
  lo_arg* arg = lo_message_get_argv(message)[0];
  switch (lo_message_get_types(message)[0]) {
    case LO_INT32:
      value = arg->i;
      return true;
    case LO_INT64:
      value = static_cast<double>(arg->h);
      return true;
    case LO_FLOAT:
      value = arg->f;
      return true;
    case LO_DOUBLE:
      value = arg->d;
      return true;
    case LO_TRUE:
      value = 1;
      return true;
    case LO_FALSE:
      value = 0;
      return true;
    default:
      return false;
  }
}

bool oneString(lo_message message, std::string& text) {
  if (lo_message_get_argc(message) != 1 || lo_message_get_types(message)[0] != LO_STRING) return false;
  text = &lo_message_get_argv(message)[0]->s;
  return true;
}

// The value of a parameter back to whoever asked, at the same address.
void reply(lo_message asked, const char* path, const ParamInfo& info, const Params& params) {
  const lo_address sender = lo_message_get_source(asked);
  if (!sender) return;
  if (info.integer())
    lo_send(sender, path, "i", params.*info.field->integer);
  else
    lo_send(sender, path, "f", params.*info.field->real);
}

}  // namespace

void addControlOptions(CLI::App& command, ControlOptions& o) {
  command
      .add_option("--control", o.port,
                  "serve OSCQuery (every parameter, cue and status) and the control page /control on this TCP port")
      ->transform(WholeNumber(1, 65535));
  command.add_option("--control-bind", o.bind, "the address --control listens on (not loopback: needs a token)")
      ->check(NotEmpty());
  command.add_option("--control-token", o.token, "a token every control request carries as ?token=...")
      ->check(NotEmpty());
  command.add_option("--presets", o.presets, "the folder of presets (/giantbubble/preset NAME)")->check(NotEmpty());
}

LiveControl::LiveControl(const ControlOptions& options, Params& wanted, OscCueReceiver& receiver)
    : params_(wanted), presets_(options.presets), bind_(options.bind) {
  state_.params.set(wanted);
  state_.presets.set(presets_.names());
  if (options.port >= 0)
    server_ = std::make_unique<ControlServer>(
        ControlServerOptions{options.port, options.bind, options.token, receiver.port()},
        makeControlRoutes(state_, receiver.port()));
  receiver.setOtherMessages([this](const char* path, void* message) { return onOsc(path, message); });
}

LiveControl::~LiveControl() = default;

std::string LiveControl::describe() const {
  if (!server_) return {};
  const std::string at = "http://" + bind_ + ":" + std::to_string(server_->port());
  return "control page at " + at + "/control, OSCQuery at " + at + "/";
}

bool LiveControl::onOsc(const char* path, void* data) {
  const auto message = static_cast<lo_message>(data);
  const std::string_view address(path);
  std::string text;
  if (address == "/giantbubble/preset" || address == "/giantbubble/preset/save") {
    if (!oneString(message, text))
      reports_.push_back(std::string(address) + " refused: it takes one string, the preset's name");
    else
      (address == "/giantbubble/preset" ? recalls_ : saves_).push_back(text);
    return true;
  }
  if (!address.starts_with(kParamPrefix)) return false;
  const std::string name(address.substr(kParamPrefix.size()));
  const ParamInfo* info = findParamInfo(name);
  double value = 0;
  if (lo_message_get_argc(message) == 0 && info) {
    reply(message, path, *info, params_.wanted());
    return true;
  }
  bool refused = false;
  if (!info)
    reports_.push_back(params_.set(printable(name, 64), 0.0, refused));  // its message names it unknown
  else if (!oneNumber(message, value))
    reports_.push_back("param " + name + " refused: it takes one number to set it, or none to read it");
  else
    reports_.push_back(params_.set(name, value, refused));
  return true;
}

void LiveControl::recall(const std::string& name) {
  Params preset;
  std::vector<std::string> listed;
  try {
    preset = presets_.load(name, &listed);
  } catch (const std::exception& e) {
    reports_.push_back("preset " + printable(name, 64) + " refused: " + e.what());
    return;
  }
  int now = 0, nextFilm = 0;
  for (const ParamInfo& info : paramCatalog()) {
    if (std::find(listed.begin(), listed.end(), info.field->name) == listed.end()) continue;
    const double value = paramValue(preset, *info.field);
    if (value == paramValue(params_.wanted(), *info.field) || info.timing == ParamTiming::Start) continue;
    bool refused = false;
    params_.set(info.field->name, value, refused);
    if (!refused) ++(info.timing == ParamTiming::NextFilm ? nextFilm : now);
  }
  reports_.push_back("preset " + name + ": " + std::to_string(now) + " parameters applied now, " +
                     std::to_string(nextFilm) + " at the next dip");
}

void LiveControl::recallNumbered(int n) {
  const std::vector<std::string> names = presets_.names();
  if (n < 1 || n > static_cast<int>(names.size()))
    reports_.push_back("key " + std::to_string(n) + ": no preset " + std::to_string(n) + " (" +
                       std::to_string(names.size()) + " saved in " + presets_.dir().string() + ")");
  else
    recalls_.push_back(names[static_cast<size_t>(n - 1)]);
}

void LiveControl::save(const std::string& name) {
  try {
    presets_.save(name, params_.wanted());
    state_.presets.set(presets_.names());
    reports_.push_back("preset " + name + " saved to " + (presets_.dir() / (name + ".toml")).string());
  } catch (const std::exception& e) {
    reports_.push_back("preset " + printable(name, 64) + " not saved: " + e.what());
  }
}

void LiveControl::flush(const Report& report) {
  const auto count = static_cast<long>(reports_.size());
  for (long k = 0; k < count && k < kMostReportsPerFrame; ++k) report(reports_[static_cast<size_t>(k)]);
  if (count > kMostReportsPerFrame)
    report("and " + std::to_string(count - kMostReportsPerFrame) + " more parameter messages this frame");
  reports_.clear();
}

void LiveControl::betweenFrames(Simulation& sim, const Report& report) {
  const auto started = std::chrono::steady_clock::now();
  for (const std::string& name : std::exchange(saves_, {})) save(name);
  for (const std::string& name : std::exchange(recalls_, {})) recall(name);
  for (const std::string& failed : params_.apply(sim)) reports_.push_back(failed);
  flush(report);
  state_.params.set(params_.wanted());
  frameThreadSeconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
}

void LiveControl::beforeDip(Simulation& sim, const Report& report) {
  for (const std::string& failed : params_.beforeDip(sim)) reports_.push_back(failed);
  flush(report);
}

void LiveControl::publish(Simulation& sim, double showTime, bool paused, const std::string& filmState,
                          const std::string& performer) {
  const auto now = std::chrono::steady_clock::now();
  ++frames_;
  if (windowShowTime_ < 0) windowShowTime_ = showTime;
  ++windowFrames_;
  const double seconds = std::chrono::duration<double>(now - windowStart_).count();
  if (seconds >= 1.0) {
    status_.framesPerSecond = static_cast<double>(windowFrames_) / seconds;
    status_.realTimeFactor = (showTime - windowShowTime_) / seconds;
    windowStart_ = now;
    windowFrames_ = 0;
    windowShowTime_ = showTime;
    // Once a second: the sums over the film cost what a frame's own statistics do.
    status_.filmArea = filmState == "none" ? 0.0 : sim.stats().area;
  }
  status_.filmState = filmState;
  status_.performer = performer;
  status_.paused = paused;
  state_.status.set(status_);
  frameThreadSeconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - now).count();
}

void LiveControl::lastEvent(const std::string& line) { status_.lastEvent = line; }

std::string LiveControl::totals() const {
  std::ostringstream text;
  text << "parameter sets: " << params_.accepted() << " taken, " << params_.refused() << " refused; show control "
       << std::fixed << std::setprecision(1) << 1e6 * frameThreadSeconds_ / static_cast<double>(std::max(frames_, 1L))
       << " us a frame on the frame thread";
  if (server_) {
    const ControlServerCounts c = server_->counts();
    text << "; control server: " << c.requests << " HTTP requests (" << c.refused << " refused), " << c.messages
         << " WebSocket messages (" << c.ignored << " ignored)";
  }
  return text.str();
}

}  // namespace gb
