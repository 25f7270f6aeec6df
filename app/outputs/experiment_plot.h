#pragma once
// A physics experiment's plot (docs/validation.md): the film's points as dots against the analytic curve as a
// line, with axes and labels. SVG.

#include <filesystem>

#include "simulation/experiments.h"

namespace gb {

// Writes the plot when the measurement has points; throws std::runtime_error when the file cannot be written.
void writeExperimentPlot(const std::filesystem::path& path, const Measurement& measurement);

}  // namespace gb
