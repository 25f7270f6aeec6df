// giantbubble: the command line. `giantbubble run` with no arguments is the README's main job: the built-in scene
// `default`, which renders its video as its [render] table says. Exit codes follow docs/user-guide.md's table:
// 0 done, 1 an error (the message names it), 3 unstable, 4 validation errors (live), 5 no video, 128 + a signal.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <string>

#include "app/commands/bench_command.h"
#include "app/commands/cli_checks.h"
#include "app/commands/evaluate_command.h"
#include "app/commands/live_command.h"
#include "app/commands/record_command.h"
#include "app/commands/run_command.h"
#include "app/commands/thread_policy.h"
#include "capture/untrusted.h"
#include "scene/scene_file.h"
#include "simulation/experiments.h"

namespace {

// Every parameter of the model can be set on the command line as --param NAME=VALUE.
void applyParameter(gb::Params& p, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos)
    throw CLI::ValidationError("--param", "expected NAME=VALUE, got '" + gb::printable(assignment) + "'");
  const std::string name = assignment.substr(0, eq), text = assignment.substr(eq + 1);
  if (!gb::findParamField(name))
    throw CLI::ValidationError("--param",
                               "unknown parameter '" + gb::printable(name) + "' (see docs/model.md for the list)");
  double value = 0;
  if (const std::string problem = gb::numberProblem(text, value); !problem.empty())
    throw CLI::ValidationError("--param", "parameter " + name + ": " + problem);
  try {
    gb::setParameter(p, name, value);
  } catch (const std::invalid_argument& e) {
    throw CLI::ValidationError("--param", e.what());
  }
}

// The value of --scene NAME or --scene=NAME, if given: the scene is the base the other options change, so it
// is read before them.
std::string sceneArgument(int argc, char** argv) {
  for (int k = 1; k < argc; ++k) {
    const std::string arg = argv[k];
    if (arg == "--scene" && k + 1 < argc) return argv[k + 1];
    if (arg.rfind("--scene=", 0) == 0) return arg.substr(8);
  }
  return {};
}

int listScenes() {
  for (const std::string& name : gb::builtinSceneNames())
    std::printf("%-18s %s\n", name.c_str(), gb::builtinScene(name).description.c_str());
  return 0;
}

// A physics experiment builds its own film and runs its own length: the options of a performance would be ignored,
// so they are refused by name.
void refuseOptionsForAnExperiment(const CLI::App& command, const std::string& experiment) {
  for (const CLI::Option* option : command.get_options()) {
    const std::string name = option->get_name();
    const bool applies = name == "--scene" || name == "--out" || name == "--param" || name == "--no-progress" ||
                         (name == "--particles" && gb::experimentSizedByParticles(experiment));
    if (option->count() > 0 && !applies)
      throw CLI::ValidationError(name, "does not apply to the physics experiment '" + experiment +
                                           "', which builds its own film and runs its own length (it takes --out, "
                                           "--param" +
                                           (gb::experimentSizedByParticles(experiment) ? ", --particles" : "") +
                                           "; docs/validation.md)");
  }
}

}  // namespace

int main(int argc, char** argv) {
  gb::setOpenMpWaiting(argv);  // before any thread starts (app/commands/thread_policy.h)
  CLI::App app{"giantbubble: real-time giant soap bubbles blown and burst with your hands"};
  app.require_subcommand(0, 1);

  gb::RunCommandLine runLine;
  runLine.scene = sceneArgument(argc, argv);
  gb::RunOptions& run = runLine.options;
  try {
    // Without --scene, the built-in scene "default" (scenes/default.toml): the giant bubble performance.
    const gb::Scene scene = gb::resolveScene(runLine.scene.empty() ? "default" : runLine.scene);
    run = scene.run;
    run.scene = scene.name;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  runLine.tool = run.tool.kind == gb::ToolKind::Ring ? "ring" : "two-wands";
  CLI::App* runCmd = gb::addRunCommand(app, runLine);
  gb::BenchOptions bench;
  CLI::App* benchCmd = gb::addBenchCommand(app, bench);
  CLI::App* scenesCmd = app.add_subcommand("scenes", "list the built-in scenes (the paper's figures), one per line");

  gb::RecordOptions record;
  CLI::App* recordCmd = gb::addRecordCommand(app, record);
  gb::EvaluateOptions evaluate;
  CLI::App* evaluateCmd = gb::addEvaluateCommand(app, evaluate);
  gb::LiveOptions view;
  view.run = run;  // the scene, if any
  view.tool = runLine.tool;
  CLI::App* viewCmd = gb::addLiveCommand(app, view);

  try {
    app.parse(argc, argv);
    for (const std::string& a : runLine.assignments) applyParameter(run.params, a);
    for (const std::string& a : view.assignments) applyParameter(view.run.params, a);
    for (const gb::Params* p : {&run.params, &view.run.params})
      if (const auto errors = gb::validate(*p); !errors.empty()) throw CLI::ValidationError("--param", errors.front());
    if (runCmd->parsed() && !run.experiment.empty()) refuseOptionsForAnExperiment(*runCmd, run.experiment);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help
    // Any mistake on the command line is an error like any other; CLI11 quotes what was given, escaped here.
    std::fprintf(stderr, "%s\nRun with --help for more information.\n", gb::printable(e.what(), 1000).c_str());
    return 1;
  }
  if (app.get_subcommands().empty()) {
    std::fputs(app.help().c_str(), stdout);
    return 0;
  }
  if (benchCmd->parsed()) return gb::runBenchmark(bench);
  if (scenesCmd->parsed()) return listScenes();
  if (viewCmd->parsed()) return gb::runLive(view);
  try {
    if (recordCmd->parsed()) return gb::runRecord(record);
    if (evaluateCmd->parsed()) return gb::runEvaluate(evaluate);
    gb::resolveRunCommandLine(runLine, *runCmd);
    return gb::runSimulation(run);
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "error: out of memory%s\n",
                 runCmd->parsed() ? " (a smaller film: --particles, or fewer outputs)" : "");
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
