#pragma once
// Soap-film physics experiments for the physical tension model (docs/validation.md): each builds its film,
// runs it on the CPU reference and measures one number that physics predicts. The tests hold the
// measurements to their bounds; `giantbubble run --scene catenoid` (and the others) shows them to a class.

#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "simulation/simulation.h"

namespace gb {

struct Measurement {
  Measurement(std::string experiment_, std::string quantity_, std::string unit_, double measured_, double analytic_,
              std::string law_)
      : experiment(std::move(experiment_)),
        quantity(std::move(quantity_)),
        unit(std::move(unit_)),
        measured(measured_),
        analytic(analytic_),
        law(std::move(law_)) {}
  std::string
      experiment;        // catenoid, catenoid-critical, young-laplace, waves, minimal-surface, flat-disc, bubble-burst
  std::string quantity;  // what was measured, in words
  std::string unit;
  double measured = 0;
  double analytic = 0;
  std::string law;  // the formula the analytic value comes from
  // What a plot of the experiment shows, when it has one: the film's points against the analytic curve.
  std::string xLabel, yLabel;
  std::vector<std::pair<double, double>> measuredPoints, analyticCurve;
  [[nodiscard]] double relativeError() const { return analytic != 0 ? (measured - analytic) / analytic : 0; }
};

// The experiments by name, in the order of docs/validation.md.
std::vector<std::string> experimentNames();

// Asked before each frame of an experiment (may be empty): true stops it with ExperimentStopped (Ctrl-C).
using StopRequest = std::function<bool()>;
struct ExperimentStopped : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Runs one experiment with the given parameters (tensionModel is set to 1 and gravity to 0; the rest is
// the caller's). `progress` is called with a line now and then (may be empty). Throws std::invalid_argument
// naming the choices for an unknown name.
Measurement runExperiment(const std::string& name, Params params,
                          const std::function<void(const std::string&)>& progress = {}, const StopRequest& stop = {});

// Whether the experiment's film is a ring film of Params::particlesAtFullSolution particles (--particles sizes it);
// the others build films of a fixed size.
bool experimentSizedByParticles(const std::string& name);

// The analytic pieces, for the tests as well.
double catenoidNeck(double ringRadius, double separation);  // stable branch of R = a cosh(d / 2a)
double neckRadius(const Film& film, const Vec3& center);    // smallest distance of a particle from the z axis
double meanCurvatureTimes(const Film& film, float length);  // mean |H| x length over the free particles

}  // namespace gb
