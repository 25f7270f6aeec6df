// giantbubble: the command line. `giantbubble run` with no arguments is the README's main job.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <map>

#include "bench_command.h"
#include "run_command.h"
#include "view_command.h"

namespace {

// Every parameter of the model can be set on the command line as --param NAME=VALUE.
void applyParameter(gb::Params& p, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos) throw CLI::ValidationError("--param", "expected NAME=VALUE, got '" + assignment + "'");
  const std::string name = assignment.substr(0, eq), text = assignment.substr(eq + 1);
  const std::map<std::string, float*> floats = {
      {"frameTime", &p.frameTime}, {"stabilitySafety", &p.stabilitySafety},
      {"elasticityWeight", &p.elasticityWeight}, {"elasticityThickness", &p.elasticityThickness},
      {"areaWeight", &p.areaWeight}, {"marangoniLifetime", &p.marangoniLifetime},
      {"springPrestrain", &p.springPrestrain}, {"springDamping", &p.springDamping}, {"filmInertia", &p.filmInertia}, {"airDrag", &p.airDrag},
      {"gravityX", &p.gravityX}, {"gravityY", &p.gravityY}, {"gravityZ", &p.gravityZ},
      {"airDirectionThreshold", &p.airDirectionThreshold}, {"airInflowDistance", &p.airInflowDistance},
      {"airPressureGain", &p.airPressureGain}, {"pressureCoefficient", &p.pressureCoefficient},
      {"thicknessThreshold", &p.thicknessThreshold}, {"sticky", &p.sticky},
      {"collisionThreshold", &p.collisionThreshold}, {"solution", &p.solution},
      {"drainageRate", &p.drainageRate}, {"surfaceTension", &p.surfaceTension}, {"liquidDensity", &p.liquidDensity},
      {"aerosolLifetime", &p.aerosolLifetime}, {"aerosolDrag", &p.aerosolDrag}, {"pinchDistance", &p.pinchDistance},
      {"collisionDistance", &p.collisionDistance}, {"collisionStiffness", &p.collisionStiffness},
      {"collisionDamping", &p.collisionDamping}};
  const std::map<std::string, int*> ints = {{"maxSubsteps", &p.maxSubsteps}, {"holeOpening", &p.holeOpening},
                                            {"particlesAtFullSolution", &p.particlesAtFullSolution}};
  size_t used = 0;
  try {
    if (auto f = floats.find(name); f != floats.end()) {
      *f->second = std::stof(text, &used);
    } else if (auto i = ints.find(name); i != ints.end()) {
      *i->second = std::stoi(text, &used);
    } else {
      throw CLI::ValidationError("--param", "unknown parameter '" + name + "' (see docs/model.md for the list)");
    }
  } catch (const std::logic_error&) {
    throw CLI::ValidationError("--param", "parameter " + name + ": '" + text + "' is not a number");
  }
  if (used != text.size()) throw CLI::ValidationError("--param", "parameter " + name + ": '" + text + "' is not a number");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"giantbubble: real-time giant soap bubbles blown and burst with your hands"};
  app.require_subcommand(0, 1);

  gb::RunOptions run;
  std::string tool = "two-wands", gesture = "straight";
  std::vector<std::string> assignments;
  CLI::App* runCmd = app.add_subcommand("run", "simulate a scripted performance headless and write its outputs");
  runCmd->add_option("--duration", run.duration, "simulated seconds")->check(CLI::Range(0.001, 3600.0));
  runCmd->add_option("--out", run.outDir, "output folder (created if missing)");
  runCmd->add_option("--ply-every", run.plyEvery, "write a PLY mesh every N frames, 0 for none")
      ->check(CLI::Range(0, 1000000));
  runCmd->add_option("--images-every", run.imageEvery, "write a thickness image (PNG) every N frames, 0 for none")
      ->check(CLI::Range(0, 1000000));
  runCmd->add_option("--tool", tool, "bubble tool")->check(CLI::IsMember({"two-wands", "ring"}));
  runCmd->add_option("--gesture", gesture, "scripted wand gesture")->check(CLI::IsMember(gb::gestureNames()));
  runCmd->add_option("--speed", run.gestureOptions.speed, "peak wand speed (m/s)")->check(CLI::Range(0.0, 20.0));
  runCmd->add_option("--solution", run.params.solution, "remaining soap solution (0, 1]")
      ->check(CLI::Range(0.01, 1.0));
  runCmd->add_option("--particles", run.params.particlesAtFullSolution, "particles of a film at full solution")
      ->check(CLI::Range(16, 50000000));
  runCmd->add_option("--param", assignments, "set a model parameter, NAME=VALUE (repeatable)");
  runCmd->add_option("--burst-at", run.burstAt, "poke the top of the film at this time (s); negative: never");
  runCmd->add_flag("!--no-progress", run.progress, "do not show the progress bar");
  std::string backend = "auto";
  runCmd->add_option("--backend", backend, "cpu, vulkan, or auto (Vulkan on a GPU, else the CPU)")
      ->check(CLI::IsMember({"cpu", "vulkan", "auto"}));
  runCmd->add_option("--device", run.device,
                     "Vulkan device: index or part of its name (default: $GIANTBUBBLE_VULKAN_DEVICE, else the best)");
  gb::addRenderOptions(*runCmd, run.render);

  gb::BenchOptions bench;
  CLI::App* benchCmd = app.add_subcommand("bench", "measure step throughput on each backend for several film sizes");
  benchCmd->add_option("--sizes", bench.sizes, "film sizes in particles")->check(CLI::Range(100, 50000000));
  benchCmd->add_option("--backends", bench.backends, "backends to measure")->check(CLI::IsMember({"cpu", "vulkan"}));
  benchCmd->add_option("--steps", bench.steps, "substeps timed per film")->check(CLI::Range(8, 100000));
  benchCmd->add_option("--json", bench.json, "where to write the results");
  benchCmd->add_option("--device", bench.device, "Vulkan device: index or part of its name");

  gb::ViewOptions view;
  CLI::App* viewCmd = gb::addViewCommand(app, view);

  try {
    app.parse(argc, argv);
    for (const std::string& a : assignments) applyParameter(run.params, a);
    if (const auto errors = gb::validate(run.params); !errors.empty()) throw CLI::ValidationError("--param", errors.front());
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  if (app.get_subcommands().empty()) {
    std::fputs(app.help().c_str(), stdout);
    return 0;
  }
  if (benchCmd->parsed()) return gb::runBenchmark(bench);
  if (viewCmd->parsed()) return gb::runView(view);
  try {
    run.tool.kind = tool == "ring" ? gb::ToolKind::Ring : gb::ToolKind::TwoWands;
    run.gesture = gb::gestureFromName(gesture);
    run.backend = gb::backendFromName(backend);
    return gb::runSimulation(run);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
