#include "params.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace gb {
namespace {

// Appends a message when value is not finite or lies outside [lo, hi].
template <class T>
void requireRange(std::vector<std::string>& errors, const char* name, T value, T lo, T hi, const char* unit) {
  if (std::isfinite(static_cast<double>(value)) && value >= lo && value <= hi) return;
  std::ostringstream msg;
  msg << "parameter " << name << " = " << value << " is out of range [" << lo << ", " << hi << "]" << unit;
  errors.push_back(msg.str());
}

#define GB_REAL(field) ParamField{#field, &Params::field, nullptr}
#define GB_INTEGER(field) ParamField{#field, nullptr, &Params::field}
// In the order of shared_params.h.
constexpr std::array kFields = {
    GB_REAL(frameTime), GB_REAL(stabilitySafety), GB_INTEGER(maxSubsteps), GB_REAL(elasticityWeight),
    GB_REAL(elasticityThickness), GB_REAL(areaWeight), GB_REAL(marangoniLifetime), GB_REAL(springPrestrain),
    GB_REAL(springDamping), GB_REAL(filmInertia), GB_REAL(airDrag), GB_REAL(gravityX), GB_REAL(gravityY),
    GB_REAL(gravityZ), GB_REAL(airDirectionThreshold), GB_REAL(airInflowDistance), GB_REAL(airPressureGain),
    GB_REAL(pressureCoefficient), GB_REAL(thicknessThreshold), GB_REAL(sticky), GB_REAL(drainageRate),
    GB_REAL(surfaceTension), GB_REAL(liquidDensity), GB_INTEGER(holeOpening), GB_REAL(aerosolLifetime),
    GB_REAL(aerosolDrag), GB_REAL(collisionThreshold), GB_REAL(collisionDistance), GB_REAL(collisionStiffness),
    GB_REAL(collisionDamping), GB_REAL(pinchDistance), GB_REAL(solution), GB_INTEGER(particlesAtFullSolution),
    GB_REAL(solutionReserve), GB_REAL(growthStretch), GB_INTEGER(airTransfer),
    GB_INTEGER(tensionModel), GB_REAL(gibbsElasticity)};
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
  if (field->real) {
    params.*field->real = static_cast<float>(value);
    return;
  }
  if (!(std::isfinite(value) && value == std::floor(value) && std::abs(value) < 2e9)) {
    std::ostringstream msg;
    msg << "parameter " << name << " = " << value << " must be a whole number";
    throw std::invalid_argument(msg.str());
  }
  params.*field->integer = static_cast<int>(value);
}

std::vector<std::string> validate(const Params& p) {
  std::vector<std::string> e;
  requireRange(e, "frameTime", p.frameTime, 1e-5f, 0.1f, " s");
  requireRange(e, "stabilitySafety", p.stabilitySafety, 0.01f, 1.0f, "");
  requireRange(e, "maxSubsteps", p.maxSubsteps, 1, 1000000, "");
  requireRange(e, "elasticityWeight", p.elasticityWeight, 1e-4f, 1e4f, " N/m");
  requireRange(e, "elasticityThickness", p.elasticityThickness, 1e-9f, 1e-3f, " m");
  requireRange(e, "areaWeight", p.areaWeight, 1e-4f, 10.0f, "");
  requireRange(e, "marangoniLifetime", p.marangoniLifetime, 0.0f, 1e6f, " s");
  requireRange(e, "springPrestrain", p.springPrestrain, 0.0f, 0.5f, "");
  requireRange(e, "springDamping", p.springDamping, 0.0f, 10.0f, " N s/m");
  requireRange(e, "filmInertia", p.filmInertia, 1e-6f, 100.0f, " kg/m^2");
  requireRange(e, "airDrag", p.airDrag, 0.0f, 100.0f, " Pa s/m");
  requireRange(e, "gravityX", p.gravityX, -100.0f, 100.0f, " m/s^2");
  requireRange(e, "gravityY", p.gravityY, -100.0f, 100.0f, " m/s^2");
  requireRange(e, "gravityZ", p.gravityZ, -100.0f, 100.0f, " m/s^2");
  requireRange(e, "airDirectionThreshold", p.airDirectionThreshold, 0.0f, 1.0f, "");
  requireRange(e, "airInflowDistance", p.airInflowDistance, 1e-3f, 100.0f, " m");
  requireRange(e, "airPressureGain", p.airPressureGain, 0.0f, 1e4f, " Pa s/m^3");
  requireRange(e, "pressureCoefficient", p.pressureCoefficient, 1.0f, 1e7f, " Pa");
  requireRange(e, "thicknessThreshold", p.thicknessThreshold, 0.0f, 1e-3f, " m");
  requireRange(e, "sticky", p.sticky, 1e-3f, 1e6f, "");
  requireRange(e, "collisionDistance", p.collisionDistance, 0.0f, 1.0f, " m");
  requireRange(e, "collisionStiffness", p.collisionStiffness, 0.0f, 1e4f, " N/m");
  requireRange(e, "collisionDamping", p.collisionDamping, 0.0f, 10.0f, " N s/m");
  requireRange(e, "drainageRate", p.drainageRate, 0.0f, 1e3f, " 1/s");
  requireRange(e, "surfaceTension", p.surfaceTension, 1e-4f, 1.0f, " N/m");
  requireRange(e, "liquidDensity", p.liquidDensity, 1.0f, 1e5f, " kg/m^3");
  requireRange(e, "holeOpening", p.holeOpening, 0, 1, "");
  requireRange(e, "aerosolLifetime", p.aerosolLifetime, 0.0f, 1e3f, " s");
  requireRange(e, "aerosolDrag", p.aerosolDrag, 0.0f, 1e3f, " 1/s");
  requireRange(e, "collisionThreshold", p.collisionThreshold, 0.0f, 1e3f, "");
  requireRange(e, "pinchDistance", p.pinchDistance, 0.0f, 10.0f, " m");
  requireRange(e, "solution", p.solution, 0.01f, 1.0f, "");
  requireRange(e, "solutionReserve", p.solutionReserve, 0.0f, 100.0f, "");
  requireRange(e, "growthStretch", p.growthStretch, 1.05f, 100.0f, "");
  requireRange(e, "airTransfer", p.airTransfer, 0, 1, "");
  requireRange(e, "tensionModel", p.tensionModel, 0, 1, "");
  requireRange(e, "gibbsElasticity", p.gibbsElasticity, 0.0f, 1.0f, " N/m");
  requireRange(e, "particlesAtFullSolution", p.particlesAtFullSolution, 16, 50000000, "");
  return e;
}

}  // namespace gb
