#include "model/params.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace gb {
namespace {

// Appends an error when value is not finite or lies outside [lo, hi].
template <class T>
void requireRange(std::vector<ParamError>& errors, const char* name, T value, T lo, T hi, const char* unit) {
  if (std::isfinite(static_cast<double>(value)) && value >= lo && value <= hi) return;
  std::ostringstream msg;
  msg << "parameter " << name << " = " << value << " is out of range [" << lo << ", " << hi << "]" << unit;
  errors.push_back({name, msg.str()});
}

#define GB_REAL(field, lo, hi, unit) \
  ParamField { #field, &Params::field, nullptr, lo, hi, unit }
#define GB_INTEGER(field, lo, hi) \
  ParamField { #field, nullptr, &Params::field, lo, hi, "" }
// In the order of shared_params.h, each with its valid range.
constexpr std::array kFields = {GB_REAL(frameTime, 1e-5, 0.1, " s"),
                                GB_INTEGER(integrator, 0, 1),
                                GB_INTEGER(solverSweeps, 1, 1000),
                                GB_INTEGER(coarseIterations, 0, 1000),
                                GB_INTEGER(coarsePatchRings, 1, 100),
                                GB_INTEGER(energyBudget, 0, 1),
                                GB_INTEGER(implicitSubsteps, 1, 1000),
                                GB_REAL(stabilitySafety, 0.01, 1.0, ""),
                                GB_INTEGER(maxSubsteps, 1, 1000000),
                                GB_REAL(elasticityWeight, 1e-4, 1e4, " N/m"),
                                GB_REAL(elasticityThickness, 1e-9, 1e-3, " m"),
                                GB_REAL(gibbsFloorThickness, 0.0, 1e-3, " m"),
                                GB_REAL(areaWeight, 1e-4, 10.0, ""),
                                GB_REAL(marangoniLifetime, 0.0, 1e6, " s"),
                                GB_REAL(springPrestrain, 0.0, 0.5, ""),
                                GB_REAL(springDamping, 0.0, 10.0, " N s/m"),
                                GB_REAL(filmInertia, 1e-6, 100.0, " kg/m^2"),
                                GB_REAL(airDrag, 0.0, 100.0, " Pa s/m"),
                                GB_REAL(gravityX, -100.0, 100.0, " m/s^2"),
                                GB_REAL(gravityY, -100.0, 100.0, " m/s^2"),
                                GB_REAL(gravityZ, -100.0, 100.0, " m/s^2"),
                                GB_REAL(airDirectionThreshold, 0.0, 1.0, ""),
                                GB_REAL(airInflowDistance, 1e-3, 100.0, " m"),
                                GB_REAL(airPressureGain, 0.0, 1e4, " Pa s/m^3"),
                                GB_REAL(pressureCoefficient, 1.0, 1e7, " Pa"),
                                GB_REAL(thicknessThreshold, 0.0, 1e-3, " m"),
                                GB_REAL(sticky, 1e-3, 1e6, ""),
                                GB_REAL(drainageRate, 0.0, 1e3, " 1/s"),
                                GB_REAL(surfaceTension, 1e-4, 1.0, " N/m"),
                                GB_REAL(liquidDensity, 1.0, 1e5, " kg/m^3"),
                                GB_INTEGER(filmFlow, 0, 1),
                                GB_REAL(liquidViscosity, 1e-5, 10.0, " Pa s"),
                                GB_REAL(surfaceRigidity, 0.0, 1.0, ""),
                                GB_REAL(evaporationRate, 0.0, 1e-5, " m/s"),
                                GB_REAL(flowViscosity, 0.0, 1.0, " m^2/s"),
                                GB_REAL(airShear, 0.0, 10.0, " Pa s/m"),
                                GB_REAL(marangoniElasticity, 0.0, 1.0, " N/m"),
                                GB_REAL(blackFilmThickness, 0.0, 1e-6, " m"),
                                GB_INTEGER(holeOpening, 0, 1),
                                GB_REAL(aerosolLifetime, 0.0, 1e3, " s"),
                                GB_REAL(aerosolDrag, 0.0, 1e3, " 1/s"),
                                GB_REAL(collisionThreshold, 0.0, 1e3, ""),
                                GB_REAL(collisionDistance, 0.0, 1.0, " m"),
                                GB_REAL(collisionStiffness, 0.0, 1e4, " N/m"),
                                GB_REAL(collisionDamping, 0.0, 10.0, " N s/m"),
                                GB_REAL(pinchDistance, 0.0, 10.0, " m"),
                                GB_REAL(loopSwingRate, 0.1, 1000.0, " rad/s"),
                                GB_INTEGER(touchWireFilm, 0, 1),
                                GB_INTEGER(wetHands, 0, 1),
                                GB_REAL(touchStrikeSpeed, 0.0, 100.0, " m/s"),
                                GB_REAL(bubbleLift, 0.0, 1.0, ""),
                                GB_REAL(solution, 0.01, 1.0, ""),
                                GB_INTEGER(particlesAtFullSolution, 16, kMaxParticles),
                                GB_REAL(solutionReserve, 0.0, 100.0, ""),
                                GB_REAL(growthStretch, 1.05, 100.0, ""),
                                GB_REAL(yieldStretch, 0.0, 100.0, ""),
                                GB_REAL(yieldThickness, 0.0, 1e-3, " m"),
                                GB_INTEGER(energyNeutralContraction, 0, 1),
                                GB_INTEGER(mergeInterval, 1, 1000),
                                GB_INTEGER(airTransfer, 0, 1),
                                GB_INTEGER(tensionModel, 0, 1),
                                GB_REAL(gibbsElasticity, 0.0, 1.0, " N/m")};
#undef GB_REAL
#undef GB_INTEGER

}  // namespace

std::span<const ParamField> paramFields() { return kFields; }

const ParamField* findParamField(const std::string& name) {
  const auto it = std::find_if(kFields.begin(), kFields.end(), [&](const ParamField& f) { return name == f.name; });
  return it == kFields.end() ? nullptr : &*it;
}

void setParameter(Params& params, const std::string& name, double value) {
  const ParamField* field = findParamField(name);
  if (!field) throw std::invalid_argument("unknown parameter '" + name + "' (docs/model.md lists them)");
  if (!(value >= field->lo && value <= field->hi)) {  // NaN too
    std::ostringstream msg;
    msg << std::setprecision(15) << "parameter " << name << " = " << value << " is out of range [" << field->lo << ", "
        << field->hi << "]" << field->unit;
    throw std::invalid_argument(msg.str());
  }
  if (field->real) {
    params.*field->real = static_cast<float>(value);
    return;
  }
  if (value != std::floor(value)) {
    std::ostringstream msg;
    msg << "parameter " << name << " = " << value << " must be a whole number";
    throw std::invalid_argument(msg.str());
  }
  params.*field->integer = static_cast<int>(value);
}

std::vector<ParamError> rangeErrors(const Params& p) {
  std::vector<ParamError> e;
  for (const ParamField& f : kFields) {
    if (f.real)
      requireRange(e, f.name, p.*f.real, static_cast<float>(f.lo), static_cast<float>(f.hi), f.unit);
    else
      requireRange(e, f.name, p.*f.integer, static_cast<int>(f.lo), static_cast<int>(f.hi), f.unit);
  }
  return e;
}

std::vector<std::string> validate(const Params& params) {
  std::vector<std::string> messages;
  for (const ParamError& error : rangeErrors(params)) messages.push_back(error.message);
  return messages;
}

}  // namespace gb
