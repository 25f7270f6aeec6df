#include "app/control/live_params.h"

#include <sstream>
#include <stdexcept>

#include "app/control/param_catalog.h"
#include "simulation/simulation.h"

namespace gb {

std::string LiveParams::set(const std::string& name, double value, bool& refused) {
  refused = true;
  const ParamInfo* info = findParamInfo(name);
  if (info && info->timing == ParamTiming::Start) {
    ++refused_;
    return "param " + name + " refused: it is fixed when the show starts (--param " + name + "=VALUE)";
  }
  Params changed = wanted_;
  try {
    setParameter(changed, name, value);  // --param's own checks and messages
  } catch (const std::invalid_argument& e) {
    ++refused_;
    return "param " + name + " refused: " + e.what();
  }
  refused = false;
  ++accepted_;
  wanted_ = changed;
  std::ostringstream text;
  text << "param " << name << " = " << paramValue(wanted_, *info->field);
  if (info->timing == ParamTiming::NextFilm) {
    nextFilmChanged_ = true;
    text << " (from the next film: it takes effect at the next dip)";
  } else {
    liveChanged_ = true;
  }
  return text.str();
}

std::vector<std::string> LiveParams::load(Simulation& sim, const Params& params) {
  try {
    sim.setParams(params);
    return {};
  } catch (const std::invalid_argument& e) {
    return {std::string("params not applied: ") + e.what() + "; the film keeps its parameters"};
  }
}

std::vector<std::string> LiveParams::apply(Simulation& sim) {
  if (!liveChanged_) return {};
  liveChanged_ = false;
  Params params = wanted_;
  for (const ParamInfo& info : paramCatalog()) {  // those of the next film keep the film's values until its dip
    if (info.timing != ParamTiming::NextFilm) continue;
    if (info.field->real)
      params.*info.field->real = sim.params().*info.field->real;
    else
      params.*info.field->integer = sim.params().*info.field->integer;
  }
  return load(sim, params);
}

std::vector<std::string> LiveParams::beforeDip(Simulation& sim) {
  if (!nextFilmChanged_ && !liveChanged_) return {};
  nextFilmChanged_ = liveChanged_ = false;
  return load(sim, wanted_);
}

}  // namespace gb
