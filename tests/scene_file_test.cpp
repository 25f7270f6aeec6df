// Scene files: the built-in scenes run; every mistake in a scene file is named with its file, line and key.
#include "scene/scene_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "app/commands/run_command.h"

namespace gb {
namespace {

// Parses and returns the SceneError message ("" when the scene is accepted).
std::string errorOf(const std::string& text) {
  try {
    (void)parseScene(text, "test.toml", std::filesystem::current_path());
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

TEST(SceneFile, EveryBuiltInSceneLoadsAndRunsAFewFramesOnTheCpu) {
  const auto names = builtinSceneNames();
  ASSERT_GE(names.size(), 22u) << "fig09a-c, fig10a-f, fig11a-b, fig12a-b, fig14b, fig14d and 7 experiments";
  // One folder per process: another worktree's test suite on the same machine runs this test too, and a
  // shared folder removed under a running test failed it.
  const auto out = std::filesystem::temp_directory_path() / ("giantbubble_scene_test_" + std::to_string(::getpid()));
  for (const std::string& name : names) {
    Scene scene = builtinScene(name);
    EXPECT_EQ(scene.name, name);
    EXPECT_FALSE(scene.description.empty()) << name;
    if (!scene.run.experiment.empty()) continue;  // physics experiments: tests/physical_tension_test.cpp
    RunOptions& run = scene.run;
    run.duration = 0.06;  // three frames
    run.backend = Backend::Cpu;
    run.progress = false;
    run.render.enabled = false;  // the default scene's video: cli_show_proof_default_scene_renders
    run.outDir = out / name;
    EXPECT_EQ(runSimulation(run), 0) << name;
    EXPECT_TRUE(std::filesystem::exists(out / name / "stats.csv")) << name;
  }
  std::filesystem::remove_all(out);
}

TEST(SceneFile, FiguresDifferInWhatTheFigureVaries) {
  EXPECT_EQ(builtinScene("fig09b").run.params.solution, 0.75f);
  EXPECT_EQ(builtinScene("fig09c").run.params.solution, 0.5f);
  EXPECT_EQ(builtinScene("fig11b").run.tool.kind, ToolKind::Ring);
  EXPECT_EQ(builtinScene("fig11b").run.params.particlesAtFullSolution, 25650);
  EXPECT_EQ(builtinScene("fig12a").run.params.airTransfer, 0);
  EXPECT_EQ(builtinScene("fig12b").run.params.airTransfer, 1);
  EXPECT_EQ(builtinScene("fig10d").run.input.spec(), "script:twisted");
}

TEST(SceneFile, AnUnknownKeyIsNamedWithItsLine) {
  const std::string e = errorOf("name = \"x\"\n\n[params]\nstiky = 25.0\n");
  EXPECT_NE(e.find("test.toml:4:"), std::string::npos) << e;
  EXPECT_NE(e.find("'stiky'"), std::string::npos) << e;
  const std::string top = errorOf("name = \"x\"\ndurration = 3\n");
  EXPECT_NE(top.find("test.toml:2:"), std::string::npos) << top;
  EXPECT_NE(top.find("'durration'"), std::string::npos) << top;
}

TEST(SceneFile, AWrongTypeIsNamed) {
  const std::string e = errorOf("name = \"x\"\nduration = \"long\"\n");
  EXPECT_NE(e.find("test.toml:2:"), std::string::npos) << e;
  EXPECT_NE(e.find("duration must be a number"), std::string::npos) << e;
  const std::string i = errorOf("name = \"x\"\n[params]\nholeOpening = 0.5\n");
  EXPECT_NE(i.find("holeOpening = 0.5 must be a whole number"), std::string::npos) << i;
  const std::string t = errorOf("name = \"x\"\n[tool]\nkind = \"trumpet\"\n");
  EXPECT_NE(t.find("'trumpet' is not one of: two-wands, ring"), std::string::npos) << t;
}

TEST(SceneFile, AnOutOfRangeValueIsNamedWithItsLine) {
  const std::string e = errorOf("name = \"x\"\n[params]\nsolution = 7.0\n");
  EXPECT_NE(e.find("test.toml:3:"), std::string::npos) << e;
  EXPECT_NE(e.find("solution = 7 is out of range"), std::string::npos) << e;
  const std::string d = errorOf("name = \"x\"\nduration = -1\n");
  EXPECT_NE(d.find("duration = -1 is out of range"), std::string::npos) << d;
}

TEST(SceneFile, AMissingInputFileIsNamed) {
  const std::string e = errorOf("name = \"x\"\n[input]\nsource = \"trajectory:nowhere.csv\"\n");
  EXPECT_NE(e.find("test.toml:3:"), std::string::npos) << e;
  EXPECT_NE(e.find("nowhere.csv' does not exist"), std::string::npos) << e;
  EXPECT_NE(errorOf("name = \"x\"\n[input]\nsource = \"script:moonwalk\"\n").find("moonwalk"), std::string::npos);
}

TEST(SceneFile, ADrawnScaleOutsideAQuarterToOneIsRefused) {
  const std::string e = errorOf("name = \"x\"\n[render]\nscale = 2.0\n");
  EXPECT_NE(e.find("test.toml:3:"), std::string::npos) << e;
  EXPECT_NE(e.find("scale"), std::string::npos) << e;
}

TEST(SceneFile, MalformedTomlIsNamedWithItsLine) {
  const std::string e = errorOf("name = \"x\"\n[params\n");
  EXPECT_NE(e.find("test.toml:2:"), std::string::npos) << e;
}

TEST(SceneFile, AnAcceptedSceneSetsWhatItSays) {
  const Scene s = parseScene(
      "name = \"mine\"\nduration = 2.5\nburst_at = 1.0\n[tool]\nkind = \"ring\"\n"
      "[input]\nsource = \"script:circles\"\nspeed = 1.5\n[params]\nsticky = 28.0\n"
      "[render]\nwidth = 640\nheight = 360\ncolouring = \"thickness\"\nscale = 0.5\n"
      "camera = [0.0, 1.2, 3.0]\ntarget = [0.0, 1.2, 0.0]\nvideo = false\nvideo_fps = 30\n",
      "test.toml", std::filesystem::current_path());
  EXPECT_EQ(s.run.duration, 2.5);
  EXPECT_EQ(s.run.burstAt, 1.0);
  EXPECT_EQ(s.run.tool.kind, ToolKind::Ring);
  EXPECT_EQ(s.run.input.spec(), "script:circles");
  EXPECT_EQ(s.run.gestureOptions.speed, 1.5f);
  EXPECT_EQ(s.run.params.sticky, 28.0f);
  EXPECT_EQ(s.run.render.image.width, 640);
  EXPECT_EQ(s.run.render.image.colouring, Colouring::Thickness);
  EXPECT_EQ(s.run.render.drawnScale, 0.5f);
  EXPECT_TRUE(s.run.render.video.empty());
  EXPECT_EQ(s.run.render.videoFps, 30.0);
  // The camera looks at the target from 3 m in front of it: the same eye position back (float rounding).
  EXPECT_LT((s.run.render.camera.position() - Vec3(0.0f, 1.2f, 3.0f)).norm(), 1e-5f);
}

}  // namespace
}  // namespace gb
