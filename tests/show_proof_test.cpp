// Show-proofing: nothing lost on a full disk, no output written onto a device or a FIFO, inputs that cannot stall the
// loop, slip a NaN past a check or grow without bound, messages that say what is wrong. The command-line halves
// (signals, ffmpeg, live recovery) are in cli_show_proof_test.sh.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "app/commands/cli_checks.h"
#include "app/commands/interrupt.h"
#include "app/outputs/osc_events.h"
#include "app/outputs/run_output.h"
#include "app/show/live_show.h"
#include "app/show/realtime_pacer.h"
#include "app/show/video_stream.h"
#include "capture/depth_recording.h"
#include "capture/freenect_stream.h"
#include "capture/hand_forest.h"
#include "capture/output_file.h"
#include "capture/png_image.h"
#include "capture/trajectory_file.h"
#include "capture/trajectory_plot.h"
#include "capture/untrusted.h"
#include "capture/wand_input.h"
#include "host/renderer.h"
#include "scene/scene_file.h"
#include "simulation/experiments.h"

namespace gb {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  static const struct Root {
    fs::path path = fs::temp_directory_path() / ("giantbubble_show_proof_test_" + std::to_string(::getpid()));
    ~Root() { fs::remove_all(path); }
  } root;
  const fs::path dir = root.path / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string readAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// A disk that is full after `bytes` more bytes in any one file: RLIMIT_FSIZE, with SIGXFSZ ignored so that a
// write past it fails with EFBIG as a write to a full disk fails with ENOSPC. Restored when it goes.
class FullDiskAfter {
 public:
  explicit FullDiskAfter(rlim_t bytes) {
    getrlimit(RLIMIT_FSIZE, &saved_);
    previous_ = std::signal(SIGXFSZ, SIG_IGN);
    rlimit limit = saved_;
    limit.rlim_cur = bytes;
    setrlimit(RLIMIT_FSIZE, &limit);
  }
  ~FullDiskAfter() {
    setrlimit(RLIMIT_FSIZE, &saved_);
    std::signal(SIGXFSZ, previous_);
  }

 private:
  rlimit saved_{};
  void (*previous_)(int) = nullptr;
};

template <typename F>
std::string errorOf(F&& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(ShowProof, StatsJsonOnAFullDiskIsAnErrorAndTheOldFileIsKept) {
  const fs::path dir = scratch("full_json");
  const fs::path json = dir / "stats.json";
  std::ofstream(json) << "{\"status\": \"the previous run\"}\n";
  RunRecord record;
  FrameStats stats;
  stats.particles = 100;
  record.start(stats);
  for (int k = 0; k < 50; ++k) record.addFrame(stats, 4, 1.0, k % 5 == 0 ? "film_grown" : "");
  std::string message;
  {
    const FullDiskAfter full(512);  // stats.json of 50 frames with events is several KB
    message = errorOf([&] { record.writeJson(json, "scene", "finished"); });
  }
  EXPECT_NE(message.find("failed writing " + json.string()), std::string::npos) << message;
  EXPECT_EQ(readAll(json), "{\"status\": \"the previous run\"}\n");  // the old file, whole
  EXPECT_FALSE(fs::exists(dir / "stats.json.partial"));
}

TEST(ShowProof, AStatsRowThatDoesNotFitStopsTheRunInsteadOfBeingCut) {
  const fs::path csv = scratch("full_csv") / "stats.csv";
  StatsWriter writer(csv);  // the header, before the disk fills
  FrameStats stats;
  std::string message;
  {
    const FullDiskAfter full(fs::file_size(csv) + 300);
    message = errorOf([&] {
      for (long frame = 0; frame < 100; ++frame) writer.write(frame, stats, 4, 1.0, "");
    });
  }
  EXPECT_NE(message.find("failed writing " + csv.string()), std::string::npos) << message;
}

TEST(ShowProof, AWholeFileIsReplacedAtomicallyAndAnUnwritablePathIsNamed) {
  const fs::path dir = scratch("atomic");
  writeFileAtomically(dir / "a.json", "first\n");
  writeFileAtomically(dir / "a.json", "second\n");
  EXPECT_EQ(readAll(dir / "a.json"), "second\n");
  const std::string message = errorOf([&] { writeFileAtomically(dir / "no_such_folder" / "a.json", "x"); });
  EXPECT_NE(message.find("cannot write " + (dir / "no_such_folder" / "a.json").string() + ": No such file"),
            std::string::npos)
      << message;
}

TEST(ShowProof, AnOutputIsNeverWrittenOntoAFifoAFolderOrADevice) {
  const fs::path dir = scratch("targets");
  const fs::path fifo = dir / "fifo.json", folder = dir / "folder.json";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  fs::create_directories(folder);
  for (const auto& target : {std::pair{fifo, "a FIFO"}, {folder, "a folder"}}) {
    const fs::path& path = target.first;  // not a structured binding: clang 14 cannot capture one in a lambda
    const std::string kind = target.second;
    const std::string whole = errorOf([&] { writeFileAtomically(path, "x"); });
    EXPECT_NE(whole.find("will not write " + path.string() + ": it is " + kind), std::string::npos) << whole;
    const std::string rows = errorOf([&] { RowFile file(path); });  // a FIFO would block the open
    EXPECT_NE(rows.find("will not write " + path.string() + ": it is " + kind), std::string::npos) << rows;
  }
  EXPECT_TRUE(fs::is_fifo(fifo));
  EXPECT_TRUE(fs::is_directory(folder));
  // A device is refused by the check alone: no byte is written to /dev/null, which a rename would have replaced.
  const std::string device = errorOf([] { (void)outputTarget("/dev/null"); });
  EXPECT_NE(device.find("will not write /dev/null: it is a character device"), std::string::npos) << device;
}

TEST(ShowProof, AnOutputThroughASymbolicLinkReplacesItsTargetAndKeepsTheLink) {
  const fs::path dir = scratch("link");
  std::ofstream(dir / "real.json") << "old\n";
  fs::create_symlink("real.json", dir / "link.json");
  writeFileAtomically(dir / "link.json", "new\n");
  EXPECT_TRUE(fs::is_symlink(dir / "link.json"));
  EXPECT_EQ(readAll(dir / "real.json"), "new\n");
}

TEST(ShowProof, ASecondRunIntoTheSameFolderIsRefusedNamingTheFirst) {
  const fs::path dir = scratch("lock") / "out";
  {
    const OutputFolder first(dir);
    const std::string message = errorOf([&] { const OutputFolder second(dir); });
    EXPECT_NE(
        message.find("another run is writing into " + dir.string() + " (process " + std::to_string(::getpid()) + ": "),
        std::string::npos)
        << message;
  }
  EXPECT_NO_THROW(const OutputFolder again(dir));  // the lock goes with the run that held it
  EXPECT_NE(errorOf([] { const OutputFolder empty(""); }).find("the output folder's name is empty (--out)"),
            std::string::npos);
  std::ofstream(dir / "file") << "x";
  EXPECT_NE(errorOf([&] { const OutputFolder file(dir / "file"); }).find("is a regular file (--out): give a folder"),
            std::string::npos);
}

TEST(ShowProof, Table1AveragesOnlyTheFramesWithAFilm) {
  const fs::path json = scratch("table1") / "stats.json";
  RunRecord record;
  FrameStats film, gone;
  film.particles = 1000;
  film.triangles = 1900;
  record.start(film);
  for (int k = 0; k < 10; ++k) record.addFrame(film, 4, 10.0, "");
  for (int k = 0; k < 30; ++k) record.addFrame(gone, 4, 1.0, "");  // the film burst: droplets only
  record.writeJson(json, "scene", "finished");
  const std::string text = readAll(json);
  // Exact: the averages of ten equal frames.
  EXPECT_NE(text.find("\"particles\": 1000.0"), std::string::npos) << text;
  EXPECT_NE(text.find("\"frame_ms\": 10.0"), std::string::npos) << text;
  EXPECT_NE(text.find("\"frames\": 40"), std::string::npos) << text;
  EXPECT_NE(text.find("\"frames_with_film\": 10"), std::string::npos) << text;
}

TEST(ShowProof, CommandLineNumbersMustBeFinite) {
  const FiniteRange range(0.0, 20.0);
  for (std::string bad : {"nan", "NaN", "inf", "-inf", "21", "-1", "fast"}) EXPECT_NE(range(bad), "") << bad;
  for (std::string good : {"0", "2.5", "20"}) EXPECT_EQ(range(good), "") << good;
}

TEST(ShowProof, AScriptedKeyFrameTooLargeIsNamed) {
  std::string why;
  EXPECT_FALSE(parseKeyPress("99999999999999999999:b", why));
  EXPECT_NE(why.find("frame 99999999999999999999 is too large"), std::string::npos) << why;
  const auto press = parseKeyPress("50:c", why);
  ASSERT_TRUE(press);
  EXPECT_EQ(press->frame, 50);
  EXPECT_EQ(press->key, 'c');
  EXPECT_FALSE(parseKeyPress("5x:b", why));
  EXPECT_FALSE(parseKeyPress("50:z", why));
}

TEST(ShowProof, AnOscPortOutOfRangeIsRefusedNotWrapped) {
  EXPECT_NE(errorOf([] { OscSender("127.0.0.1:99999"); }).find("from 1 to 65535"), std::string::npos);
  EXPECT_NE(errorOf([] { OscSender("127.0.0.1:0"); }).find("from 1 to 65535"), std::string::npos);
  EXPECT_NO_THROW(OscSender("127.0.0.1:65535"));
}

// A PNG whose IHDR chunk claims width x height (CRCs correct, no image data).
void writePngHeader(const fs::path& path, uint32_t width, uint32_t height) {
  std::string ihdr = "IHDR";
  for (uint32_t v : {width, height})
    for (int shift = 24; shift >= 0; shift -= 8) ihdr += static_cast<char>((v >> shift) & 0xff);
  ihdr += std::string("\x08\x02\x00\x00\x00", 5);  // 8-bit RGB, no interlace
  const uLong crc = crc32(0, reinterpret_cast<const Bytef*>(ihdr.data()), static_cast<uInt>(ihdr.size()));
  std::string png = "\x89PNG\r\n\x1a\n";
  png += std::string("\x00\x00\x00\x0d", 4) + ihdr;
  for (int shift = 24; shift >= 0; shift -= 8) png += static_cast<char>((crc >> shift) & 0xff);
  // An empty IDAT: libpng reads the header up to the first IDAT, where readPng must stop and check.
  const uLong idatCrc = crc32(0, reinterpret_cast<const Bytef*>("IDAT"), 4);
  png += std::string("\x00\x00\x00\x00IDAT", 8);
  for (int shift = 24; shift >= 0; shift -= 8) png += static_cast<char>((idatCrc >> shift) & 0xff);
  std::ofstream(path, std::ios::binary) << png;
}

TEST(ShowProof, APngHeaderClaimingAHugeImageIsRefusedBeforeAllocating) {
  const fs::path png = scratch("png") / "huge.png";
  writePngHeader(png, 200000, 100000);  // 60 GB of RGB if believed
  const std::string message = errorOf([&] { (void)readPng(png); });
  EXPECT_NE(message.find("is 200000x100000 pixels; at most 16384 on a side"), std::string::npos) << message;
}

TEST(ShowProof, SceneCameraAndTargetMustBeFiniteCoordinates) {
  for (const char* bad : {"camera = [nan, 1.0, 3.0]", "target = [0.0, inf, 0.0]", "camera = [1e9, 0, 0]"}) {
    const std::string message = errorOf(
        [&] { (void)parseScene(std::string("name = \"s\"\n[render]\n") + bad + "\n", "s.toml", fs::current_path()); });
    EXPECT_NE(message.find("s.toml:3:"), std::string::npos) << message;
    EXPECT_NE(message.find("is not a coordinate within 1000 m"), std::string::npos) << message;
  }
}

TEST(ShowProof, ASceneThatIsAFolderOrAFifoIsNamedNotReadOrWaitedOn) {
  const fs::path dir = scratch("scene_kinds");
  EXPECT_NE(errorOf([&] { (void)resolveScene(dir.string()); }).find("is a folder"), std::string::npos);
  const fs::path fifo = dir / "scene.toml";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_NE(errorOf([&] { (void)resolveScene(fifo.string()); }).find("is a FIFO (a scene is read from a regular file)"),
            std::string::npos);
}

TEST(ShowProof, AnIntegerTooLargeForTomlKeepsItsFileAndLine) {
  const std::string message = errorOf(
      [] { (void)parseScene("name = \"s\"\n[params]\nmaxSubsteps = 9999999999999\n", "s.toml", fs::current_path()); });
  EXPECT_NE(message.find("s.toml:3:15: parameter maxSubsteps"), std::string::npos) << message;
}

TEST(ShowProof, TrajectorySamplesANanosecondApartDoNotStallTheLoop) {
  // Two samples 1 ns apart, then 10 s of run: the holds through the gap go at least kMinSamplePeriod apart
  // (10,000 stabilizer updates); at the input's own period, 1 ns, it would be 10^10.
  std::vector<HandSample> samples(2);
  samples[1].time = 1e-9;
  for (HandSample& s : samples)
    for (HandObservation* o : {&s.left, &s.right}) {
      o->measured = true;
      o->confidence = 1.0;
      o->position = Vec3d(0.2, 0.0, 2.0);
    }
  StabilizedWands wands(std::make_unique<ReplayHandSource>(samples, "dense"), StabilizerOptions{}, Calibration{});
  const WandFrame f = wands.at(10.0);
  EXPECT_TRUE(f.wands.leftPosition.allFinite());
  EXPECT_TRUE(wands.ended());
}

TEST(ShowProof, ATrajectoryHeaderWithAByteOrderMarkIsRead) {
  const fs::path csv = scratch("bom") / "hands.csv";
  std::ofstream(csv)
      << "\xEF\xBB\xBFt,left_x,left_y,left_z,right_x,right_y,right_z\n0,0,0,2,0.3,0,2\n0.1,0,0,2,0.3,0,2\n";
  EXPECT_EQ(readTrajectory(csv).size(), 2u);
}

TEST(ShowProof, ATrajectoryThatIsNoFileOrHoldsHostileTextIsNamedShortly) {
  const fs::path dir = scratch("hostile_trajectory");
  fs::create_symlink("/dev/zero", dir / "zero.csv");
  fs::create_symlink("loop.csv", dir / "loop.csv");
  EXPECT_NE(errorOf([&] { (void)readTrajectory(dir / "zero.csv"); }).find("zero.csv: is a character device"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { (void)readTrajectory(dir / "loop.csv"); }).find("Too many levels of symbolic links"),
            std::string::npos);
  const std::string header = "t,left_x,left_y,left_z,right_x,right_y,right_z\n";
  std::ofstream(dir / "long.csv") << header << "0," << std::string(10 << 20, '7') << "x,0,2,0.3,0,2\n";
  const std::string longField = errorOf([&] { (void)readTrajectory(dir / "long.csv"); });
  EXPECT_LT(longField.size(), 300u) << "a 10 MB line is refused by its length, not read or echoed";
  EXPECT_NE(longField.find("line 2: longer than 4096 bytes"), std::string::npos) << longField.substr(0, 300);
  std::ofstream(dir / "field.csv") << header << "0," << std::string(1000, '7') << "x,0,2,0.3,0,2\n";
  const std::string field = errorOf([&] { (void)readTrajectory(dir / "field.csv"); });
  EXPECT_NE(field.find("...(1001 bytes)' is not a number"), std::string::npos) << field;
  const char nulRow[] = "0,1\0x,0,2,0.3,0,2\n";
  std::ofstream(dir / "nul.csv") << header << std::string(nulRow, sizeof nulRow - 1);
  const std::string nul = errorOf([&] { (void)readTrajectory(dir / "nul.csv"); });
  EXPECT_NE(nul.find("left_x '1\\0x' is not a number"), std::string::npos) << nul;
  std::ofstream(dir / "far.csv") << header << "0,-1000000,0,2,1000000,0,2\n";
  const std::string far = errorOf([&] { (void)readTrajectory(dir / "far.csv"); });
  EXPECT_NE(far.find("line 2: left_x -1000000 m is more than 100 m from the camera (a trajectory is in metres)"),
            std::string::npos)
      << far;
}

TEST(ShowProof, ALongTrajectoryIsReadOnlyAsFarAsTheRunAndTheRowLimitGo) {
  const fs::path csv = scratch("long_trajectory") / "hands.csv";
  {
    std::ofstream out(csv);
    out << "t,left_x,left_y,left_z,right_x,right_y,right_z\n0,,,,,,\n";  // hands found from t = 1 s
    for (int k = 1; k <= 1000; ++k) out << k << ",-0.2,0,2,0.2,0,2\n";
  }
  std::string cut;
  // Exact: 1 s without hands, then rows to 1 + 10 s and the first row past it, which the run's end falls before.
  const auto run = readTrajectory(csv, 0.5, TrajectoryLimits{10.0}, &cut);
  EXPECT_EQ(run.size(), 13u);
  EXPECT_EQ(cut,
            "note: trajectory file " + csv.string() + ", line 15: past the run's end; the rows from here are not read");
  const auto rows = readTrajectory(csv, 0.5, TrajectoryLimits{1e9, 100}, &cut);
  EXPECT_EQ(rows.size(), 100u);
  EXPECT_NE(cut.find("line 102: 100 rows read, the most a trajectory may have"), std::string::npos) << cut;
  EXPECT_EQ(readTrajectory(csv).size(), 1001u) << "a file within the limits is read whole";
}

TEST(ShowProof, AFakenectEntryThatIsNoFileIsNamedForWhatItIs) {
  const fs::path dir = scratch("fakenect_kinds");
  fs::create_directories(dir / "d-1.000000-100.pgm");
  std::ofstream(dir / "INDEX.txt") << "d-1.000000-100.pgm\n";
  const std::string folder = errorOf([&] { (void)readFakenectIndex(dir); });
  EXPECT_NE(folder.find("INDEX.txt line 1: file " + (dir / "d-1.000000-100.pgm").string() + " is a folder"),
            std::string::npos)
      << folder;
  fs::remove(dir / "d-1.000000-100.pgm");
  ASSERT_EQ(::mkfifo((dir / "d-1.000000-100.pgm").c_str(), 0600), 0);
  EXPECT_NE(errorOf([&] { (void)readFakenectIndex(dir); }).find("is a FIFO"), std::string::npos);
  fs::remove(dir / "d-1.000000-100.pgm");
  fs::create_symlink("/dev/zero", dir / "d-1.000000-100.pgm");
  EXPECT_NE(errorOf([&] { (void)readFakenectIndex(dir); }).find("is a character device"), std::string::npos);
  // A file name from INDEX.txt is quoted escaped: an empty file whose name holds an escape sequence.
  const std::string painted = "d-1.000000-100\x1b[31m.pgm";
  fs::remove(dir / "d-1.000000-100.pgm");
  std::ofstream(dir / painted).flush();
  std::ofstream(dir / "INDEX.txt") << painted << "\n";
  const std::string empty = errorOf([&] { (void)readFakenectIndex(dir); });
  EXPECT_NE(empty.find("d-1.000000-100\\x1b[31m.pgm is empty"), std::string::npos) << empty;
  EXPECT_EQ(empty.find('\x1b'), std::string::npos) << "no escape sequence reaches the terminal";
  fs::remove(dir / "INDEX.txt");
  fs::create_symlink("/dev/zero", dir / "INDEX.txt");  // would be read for ever
  EXPECT_NE(errorOf([&] { (void)readFakenectIndex(dir); }).find("INDEX.txt is a character device"), std::string::npos);
}

TEST(ShowProof, ASceneThatIsASymbolicLinkLoopIsNamedAsSuch) {
  const fs::path dir = scratch("scene_loop");
  fs::create_symlink("loop.toml", dir / "loop.toml");
  const std::string message = errorOf([&] { (void)resolveScene((dir / "loop.toml").string()); });
  EXPECT_NE(message.find("cannot be read: Too many levels of symbolic links"), std::string::npos) << message;
}

TEST(ShowProof, AParameterOutOfRangeIsNamedWithTheValueAsGiven) {
  Params p;
  // One limit on particles whatever sets them: the parameter as --particles.
  EXPECT_EQ(errorOf([&] { setParameter(p, "particlesAtFullSolution", 10'000'000); }),
            "parameter particlesAtFullSolution = 10000000 is out of range [16, 2000000]");
  EXPECT_EQ(errorOf([&] { setParameter(p, "particlesAtFullSolution", 2e9); }),
            "parameter particlesAtFullSolution = 2000000000 is out of range [16, 2000000]");
  EXPECT_EQ(errorOf([&] { setParameter(p, "frameTime", 1e-50); }),
            "parameter frameTime = 1e-50 is out of range [1e-05, 0.1] s");
  const std::string scene = errorOf([] {
    (void)parseScene("name = \"big\"\n[params]\nparticlesAtFullSolution = 50000000\n", "big.toml", fs::current_path());
  });
  EXPECT_NE(scene.find("big.toml:3:"), std::string::npos) << scene;
  EXPECT_NE(scene.find("= 50000000 is out of range [16, 2000000]"), std::string::npos) << scene;
}

TEST(ShowProof, FilmGenerationNamesTheOptionsAndTheInputsUnits) {
  Params p;
  p.solution = 0.01f;
  p.particlesAtFullSolution = 300;
  const WandState wands = gestureAt(Gesture::Straight, GestureOptions{}, 0.0);
  const std::string few = errorOf([&] { Simulation sim(p, WandTool{}, wands); });
  EXPECT_NE(few.find("a film of 16 particles (particlesAtFullSolution x solution: --particles, --solution) is too few"),
            std::string::npos)
      << few;
  WandState far;
  far.leftPosition = Vec3(-1e6f, 1.5f, 0);
  far.rightPosition = Vec3(1e6f, 1.5f, 0);
  const std::string distant = errorOf([&] { Simulation sim(Params{}, WandTool{}, far); });
  EXPECT_NE(distant.find("the wands are 1e+06 m from the origin, beyond 1000 m"), std::string::npos) << distant;
}

TEST(ShowProof, AnIpv6OrMalformedOscTargetIsRefusedAsSuch) {
  for (const char* target : {"[::1]:9000", "::1:9000", "127.0.0.1:9000:1"})
    EXPECT_NE(errorOf([&] { OscSender sender(target); }).find("IPv6 is not supported"), std::string::npos) << target;
}

TEST(ShowProof, APokeWithNoFilmLeftIsNoPoke) {
  Params p;
  p.particlesAtFullSolution = 400;
  const WandState wands = gestureAt(Gesture::Straight, GestureOptions{}, 0.0);
  Simulation sim(p, WandTool{}, wands);
  ASSERT_TRUE(pokeTop(sim));
  for (int frame = 0; frame < 250 && sim.stats().particles > 0; ++frame) sim.advanceFrame(wands);
  ASSERT_EQ(sim.stats().particles, 0u) << "the poked film burst within 5 s";
  EXPECT_GT(sim.film().state.size(), 0u) << "its particles linger, dead";
  EXPECT_FALSE(pokeTop(sim)) << "nothing to poke: no poked event, no B: burst";
}

TEST(ShowProof, ANegativeScriptedKeyFrameIsRefused) {
  std::string why;
  EXPECT_FALSE(parseKeyPress("-5:b", why));
  EXPECT_EQ(why, "--keys -5:b: frame -5 is negative (frames count from 0)");
}

TEST(ShowProof, ASceneNameWithControlCharactersIsRefused) {
  const std::string message =
      errorOf([] { (void)parseScene("name = \"show\\n\\u001b[31mred\"\n", "s.toml", fs::current_path()); });
  EXPECT_NE(message.find("s.toml:1:"), std::string::npos) << message;
  EXPECT_NE(message.find("name = 'show\\n\\x1b[31mred' holds control characters"), std::string::npos) << message;
  EXPECT_EQ(message.find('\x1b'), std::string::npos) << "the message itself holds no escape";
  const std::string input = errorOf([] {
    (void)parseScene("name = \"s\"\n[input]\nsource = \"trajectory:\\u001b[2Jgone.csv\"\n", "s.toml", "/nowhere");
  });
  EXPECT_NE(input.find("input file '/nowhere/\\x1b[2Jgone.csv' does not exist"), std::string::npos) << input;
  EXPECT_EQ(input.find('\x1b'), std::string::npos) << "a path from a scene is quoted escaped too";
}

TEST(ShowProof, ARenderSizeIsBoundedByTheDevice) {
  EXPECT_EQ(renderSizeProblem(1280, 720, 4, 16384, 16e9, "gpu"), "");
  EXPECT_EQ(renderSizeProblem(16384, 16384, 1, 8192, 1e12, "gpu"),
            "render size 16384x16384 is outside 16..8192 pixels on gpu (--width, --height)");
  // 16384 x 16384 at one sample: 34 bytes a pixel (renderTargetBytes), 9.1 GB, beyond a quarter of 16 GB.
  EXPECT_EQ(renderSizeProblem(16384, 16384, 1, 16384, 16e9, "gpu"),
            "a 16384x16384 image at 1 sample per pixel takes 9.1 GB of render targets, more than a quarter of the "
            "16.0 GB of gpu: give a smaller --width and --height");
}

TEST(ShowProof, AnExperimentStopsBetweenFramesWhenAsked) {
  int asked = 0;
  const auto stopAtThird = [&] { return ++asked == 3; };
  Params small;
  small.particlesAtFullSolution = 400;
  const std::string message = errorOf([&] { (void)runExperiment("flat-disc", small, {}, stopAtThird); });
  EXPECT_EQ(message.rfind("stopped at t = 0.04", 0), 0u) << message;  // two frames of 0.02 s ran
}

// Untrusted input on its way into a message (capture/untrusted.h): paths that are not regular files are named for
// what they are, and text from files is escaped and cut before it reaches a terminal.
TEST(Untrusted, APathThatIsNoRegularFileIsNamedForWhatItIs) {
  const fs::path dir = scratch("kinds");
  std::ofstream(dir / "file.csv") << "t\n";
  ASSERT_EQ(::mkfifo((dir / "fifo.csv").c_str(), 0600), 0);
  fs::create_symlink("/dev/zero", dir / "zero.csv");
  fs::create_symlink("loop.csv", dir / "loop.csv");
  EXPECT_EQ(whyNotARegularFile(dir / "file.csv"), "");
  EXPECT_EQ(whyNotARegularFile(dir / "missing.csv"), "does not exist");
  EXPECT_EQ(whyNotARegularFile(dir), "is a folder");
  EXPECT_EQ(whyNotARegularFile(dir / "fifo.csv"), "is a FIFO");
  EXPECT_EQ(whyNotARegularFile(dir / "zero.csv"), "is a character device");
  EXPECT_EQ(whyNotARegularFile(dir / "loop.csv"), "cannot be read: Too many levels of symbolic links");
}

TEST(Untrusted, ControlCharactersAreEscapedAndLongTextIsCut) {
  EXPECT_EQ(printable("fig10a"), "fig10a");
  EXPECT_EQ(printable("red\n\x1b[31mtext"), "red\\n\\x1b[31mtext");
  EXPECT_EQ(printable(std::string("a\0b", 3)), "a\\0b");  // a NUL no longer ends the message
  EXPECT_EQ(printable("caf\xc3\xa9 \xe2\x80\x94 ok"), "caf\xc3\xa9 \xe2\x80\x94 ok");  // UTF-8 text stays
  EXPECT_EQ(printable("\xc2\x9b"
                      "31m"),
            "\\xc2\\x9b31m");                      // the one-byte CSI (U+009B) is a control character
  EXPECT_EQ(printable("\xff\xfe"), "\\xff\\xfe");  // bytes that are not UTF-8
  const std::string field(10 << 20, '7');          // a 10 MB CSV field
  EXPECT_EQ(printable(field), std::string(kMaxQuotedBytes, '7') + "...(10485760 bytes)");
}

TEST(Untrusted, DirectionControlsAreEscaped) {
  // A right-to-left override (U+202E) and an isolate (U+2066) would show the rest of a message in another order.
  EXPECT_EQ(printable("show\xe2\x80\xaegnp.exe"), "show\\u202egnp.exe");
  EXPECT_EQ(printable("a\xe2\x81\xa6"
                      "b"),
            "a\\u2066b");
  EXPECT_EQ(printable("\xd8\x9c"), "\\u061c");
  EXPECT_EQ(printable("\xe2\x80\x94"), "\xe2\x80\x94");  // an em dash is text
}

// The third round: every output of every command written as `run`'s are, every input bounded before it is read,
// and numbers, signals and messages as the docs say.

TEST(ShowProof, ARecordedTrajectoryOnAFullDiskKeepsTheOldFileAndNamesTheReason) {
  const fs::path csv = scratch("full_trajectory") / "hands.csv";
  std::ofstream(csv) << "the previous recording\n";
  HandSample sample;
  sample.left.measured = sample.right.measured = true;
  sample.left.position = sample.right.position = Vec3d(0.1, 0.0, 2.0);
  std::string message;
  {
    const FullDiskAfter full(2000);  // a row is about 70 bytes
    message = errorOf([&] {
      TrajectoryWriter writer(csv);
      for (int k = 0; k < 100; ++k) {
        sample.time = k / 30.0;
        writer.write(sample);
      }
      writer.close();
    });
  }
  EXPECT_NE(message.find("failed writing " + csv.string() + ": File too large"), std::string::npos) << message;
  EXPECT_EQ(readAll(csv), "the previous recording\n");
  EXPECT_FALSE(fs::exists(csv.string() + ".partial"));
  TrajectoryWriter writer(csv);  // a recording that ends is renamed over the old one
  writer.write(sample);
  EXPECT_EQ(readAll(csv), "the previous recording\n") << "the old file stays while the recording goes on";
  writer.close();
  EXPECT_EQ(readTrajectory(csv).size(), 1u);
}

TEST(ShowProof, ARecordingsOutputsAreCheckedBeforeAnythingIsWritten) {
  const fs::path dir = scratch("record_outputs");
  ASSERT_EQ(::mkfifo((dir / "fifo.csv").c_str(), 0644), 0);
  const auto refusal = [](std::vector<Output> outputs) { return errorOf([&] { (void)checkOutputs(outputs); }); };
  using Kind = Output::Kind;
  EXPECT_NE(refusal({{"--trajectory", dir / "fifo.csv", Kind::File, ".csv"}})
                .find("--trajectory: will not write " + (dir / "fifo.csv").string() + ": it is a FIFO"),
            std::string::npos);
  EXPECT_NE(refusal({{"--trajectory", "/dev/null", Kind::File, ""}}).find("it is a character device"),
            std::string::npos);
  // One file named twice, also through a symbolic link to a file that does not exist yet.
  fs::create_symlink("t.csv", dir / "link.svg");
  EXPECT_NE(
      refusal({{"--trajectory", dir / "t.csv", Kind::File, ".csv"}, {"--plot", dir / "link.svg", Kind::File, ".svg"}})
          .find("--trajectory " + (dir / "t.csv").string() + " and --plot " + (dir / "link.svg").string() +
                " are one file"),
      std::string::npos);
  // A file inside the folder a fakenect recording fills.
  EXPECT_NE(refusal({{"--fakenect", dir / "rec", Kind::NewFolder, "", true},
                     {"--trajectory", dir / "rec" / "hands.csv", Kind::File, ".csv"}})
                .find("is inside --fakenect " + (dir / "rec").string() + ", which the command fills"),
            std::string::npos);
  // The extension says the format.
  EXPECT_NE(refusal({{"--depth-plot", dir / "x.svg", Kind::File, ".png"}})
                .find("--depth-plot: " + (dir / "x.svg").string() + " does not end in .png"),
            std::string::npos);
  EXPECT_EQ(refusal({{"--depth-plot", dir / "X.PNG", Kind::File, ".png"}}), "(no error)");
  // An empty name, a name too long for the file system, a folder that is missing or is a file.
  EXPECT_NE(refusal({{"--json", "", Kind::File, ".json"}}).find("--json: the name is empty: give a file"),
            std::string::npos);
  EXPECT_NE(refusal({{"--out", dir / std::string(300, 'a'), Kind::Folder, "", true}}).find("File name too long"),
            std::string::npos);
  EXPECT_NE(refusal({{"--json", dir / "missing" / "b.json", Kind::File, ".json"}})
                .find("--json: cannot write " + (dir / "missing" / "b.json").string() + ": No such file or directory"),
            std::string::npos);
  fs::create_symlink("nowhere/deep", dir / "dangling");
  EXPECT_NE(refusal({{"--out", dir / "dangling", Kind::Folder, "", true}})
                .find("is a symbolic link to nowhere/deep, which does not exist: give a folder"),
            std::string::npos);
  EXPECT_TRUE(fs::is_fifo(dir / "fifo.csv"));
  EXPECT_FALSE(fs::exists(dir / "rec"));
}

TEST(ShowProof, AFileInAFolderARunHoldsIsRefusedNamingTheRun) {
  const fs::path dir = scratch("held_folder") / "out";
  const OutputFolder run(dir);
  const std::string message = errorOf([&] {
    (void)checkOutputs({{"--trajectory", dir / "stats.csv", Output::Kind::File, ".csv"}});
  });
  EXPECT_NE(message.find("another run is writing into " + dir.string() + " (process " + std::to_string(::getpid())),
            std::string::npos)
      << message;
  EXPECT_FALSE(fs::exists(dir / "stats.csv"));
}

TEST(ShowProof, AFileAnotherProcessIsWritingIsRefusedAndALeftoverPartialReplaced) {
  const fs::path dir = scratch("partial");
  const fs::path video = dir / "show.mp4";
  {
    const PartialFile first(video);  // held, as by a run whose ffmpeg writes it
    EXPECT_NE(errorOf([&] {
                const PartialFile second(video);
              }).find("another process is writing " + video.string() + " (it holds " + video.string() + ".partial)"),
              std::string::npos);
    EXPECT_NE(errorOf([&] {
                (void)checkOutputs({{"--video", video, Output::Kind::File, ".mp4"}});
              }).find("--video: another process is writing"),
              std::string::npos);
  }
  EXPECT_FALSE(fs::exists(video.string() + ".partial")) << "an uncommitted partial file goes";
  std::ofstream(dir / "x.json.partial") << "left by a process killed while writing";
  writeFileAtomically(dir / "x.json", "{}\n");
  EXPECT_EQ(readAll(dir / "x.json"), "{}\n");
  ASSERT_EQ(::mkfifo((dir / "y.json.partial").c_str(), 0644), 0);
  EXPECT_NE(errorOf([&] {
              writeFileAtomically(dir / "y.json", "{}");
            }).find("y.json.partial is a FIFO, not a file left by an earlier write"),
            std::string::npos);
  EXPECT_TRUE(fs::is_fifo(dir / "y.json.partial")) << "a FIFO is not removed";
}

TEST(ShowProof, ATrajectoryPlotIsWrittenWholeOrNotAtAll) {
  const fs::path svg = scratch("plot") / "hands.svg";
  std::ofstream(svg) << "<svg>the previous plot</svg>\n";
  TrajectoryPlot plot;
  plot.title = "test";
  for (int k = 0; k < 2000; ++k) {
    plot.leftWand.push_back(Vec3(0.01f * static_cast<float>(k), 1.0f, 0.0f));
    plot.rightWand.push_back(Vec3(0.01f * static_cast<float>(k), 1.2f, 0.0f));
  }
  std::string message;
  {
    const FullDiskAfter full(4096);  // 4000 points are tens of KB
    message = errorOf([&] { writeTrajectoryPlot(svg, plot); });
  }
  EXPECT_NE(message.find("failed writing " + svg.string() + ": File too large"), std::string::npos) << message;
  EXPECT_EQ(readAll(svg), "<svg>the previous plot</svg>\n");
}

TEST(ShowProof, AnInputThatIsNoRegularFileIsNamedWithoutWaitingOnIt) {
  const fs::path dir = scratch("inputs");
  const fs::path fifo = dir / "fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  std::string why;
  EXPECT_FALSE(openInputFile(fifo, 1 << 20, why));  // would block in open() without a writer
  EXPECT_EQ(why, "is a FIFO");
  EXPECT_FALSE(openInputFile(dir, 1 << 20, why));
  EXPECT_EQ(why, "is a folder");
  EXPECT_FALSE(openInputFile("/dev/zero", 1 << 20, why));
  EXPECT_EQ(why, "is a character device");
  std::ofstream(dir / "big") << std::string(3 << 20, 'x');
  EXPECT_FALSE(openInputFile(dir / "big", 1 << 20, why));
  EXPECT_EQ(why, "is 3.0 MiB, more than the 1.0 MiB such a file may have");
  for (const fs::path& path : {fifo, fs::path(dir), fs::path("/dev/zero")}) {
    EXPECT_NE(
        errorOf([&] { (void)readHandForest(path.string()); }).find("hand forest model " + path.string() + " is a"),
        std::string::npos);
    EXPECT_NE(errorOf([&] { (void)readPng(path); }).find("PNG " + path.string() + " is a"), std::string::npos);
  }
}

TEST(ShowProof, AHandForestWithANanThresholdOrTrailingBytesIsRefused) {
  DecisionTree tree;
  tree.nodes.resize(3);
  tree.nodes[0] = {{{{100, 0}}, {{0, 0}}}, NAN, 1};
  tree.nodes[1].next = -1;
  tree.nodes[2].next = -2;
  tree.leaves = {{1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}};
  HandForest forest;
  forest.trees = {tree};
  std::vector<uint8_t> bytes = forest.serialize();
  EXPECT_NE(
      errorOf([&] { (void)HandForest::deserialize(bytes.data(), bytes.size()); }).find("a threshold is not a number"),
      std::string::npos);
  forest.trees[0].nodes[0].threshold = 0.5f;
  bytes = forest.serialize();
  EXPECT_NO_THROW((void)HandForest::deserialize(bytes.data(), bytes.size()));
  bytes.push_back(0);
  EXPECT_NE(errorOf([&] {
              (void)HandForest::deserialize(bytes.data(), bytes.size());
            }).find("bytes after its compressed payload"),
            std::string::npos);
}

TEST(ShowProof, APngOfTooManyPixelsIsRefusedBeforeAllocating) {
  const fs::path png = scratch("png_pixels") / "sky.png";
  writePngHeader(png, 16384, 8192);  // within 16384 on a side: 400 MB of RGB if believed
  const std::string message = errorOf([&] { (void)readPng(png); });
  EXPECT_NE(message.find("is 16384x8192 pixels; at most 8192x4096 in all"), std::string::npos) << message;
}

TEST(ShowProof, AFakenectTimeThatDoesNotAdvanceIsRefused) {
  const fs::path dir = scratch("fakenect_time");
  const std::string header = "P5 640 480 65535\n";
  std::ofstream(dir / "d-1.000000-100.pgm", std::ios::binary) << header << std::string(640 * 480 * 2, '\0');
  {
    std::ofstream index(dir / "INDEX.txt");
    for (int k = 0; k < 10; ++k) index << "d-1.000000-100.pgm\n";  // one frame, ten times, at one time
  }
  const std::string message = errorOf([&] { (void)readFakenectIndex(dir); });
  EXPECT_NE(message.find("INDEX.txt line 2: time 1.000000 is not after the previous depth frame's"), std::string::npos)
      << message;
  std::ofstream(dir / "a-1.000000-100.dump", std::ios::binary) << "12345";  // a tilt state is longer
  std::ofstream(dir / "INDEX.txt") << "a-1.000000-100.dump\nd-1.000000-100.pgm\n";
  EXPECT_NE(errorOf([&] { (void)readFakenectIndex(dir); }).find("a-1.000000-100.dump is 5 bytes, expected"),
            std::string::npos);
  {
    std::ofstream index(dir / "INDEX.txt");
    for (int k = 0; k < 5; ++k) index << "r-2.000000-100.pgm\n";  // colour images: no depth frame to check
  }
  std::ofstream(dir / "r-2.000000-100.pgm", std::ios::binary)
      << "P6 640 480 255\n"
      << std::string(640 * 480 * 3, '\0');  // a colour image fakenect would read
  EXPECT_NE(errorOf([&] { (void)readFakenectIndex(dir); }).find("line 4: 4 entries at time 2.000000"),
            std::string::npos);
  // A time of 1e308 is named as written, not as 309 digits; a line of 5000 bytes is not read.
  std::ofstream(dir / "INDEX.txt") << "d-1.000000-100.pgm\nd-1e308-101.pgm\n";
  const std::string huge = errorOf([&] { (void)readFakenectIndex(dir); });
  EXPECT_NE(huge.find("line 2: time 1e308 jumps 1e+308 s forward"), std::string::npos) << huge;
  std::ofstream(dir / "INDEX.txt") << "d-1.000000-100.pgm\n" << std::string(5000, 'd') << "\n";
  EXPECT_NE(errorOf([&] { (void)readFakenectIndex(dir); }).find("line 2: longer than 4096 bytes"), std::string::npos);
}

TEST(ShowProof, ATrajectoryHandBehindTheCameraIsRefused) {
  const fs::path csv = scratch("behind") / "hands.csv";
  std::ofstream(csv) << "t,left_x,left_y,left_z,right_x,right_y,right_z\n0,0,0,2,0.3,0,-0.5\n";
  EXPECT_NE(
      errorOf([&] { (void)readTrajectory(csv); }).find("line 2: right_z -0.5 m puts the right hand behind the camera"),
      std::string::npos);
}

TEST(ShowProof, ATrajectoryHeaderFromAnyOtherFileIsNotQuoted) {
  const fs::path csv = scratch("header") / "secret.csv";
  std::ofstream(csv) << "root:x:0:0:root:/root:/bin/bash\n";
  const std::string message = errorOf([&] { (void)readTrajectory(csv); });
  EXPECT_NE(message.find("line 1: expected the header"), std::string::npos) << message;
  EXPECT_EQ(message.find("root:x"), std::string::npos) << message;
}

TEST(ShowProof, ADeepOrLinkedArchiveEntryIsNamed) {
  const fs::path dir = scratch("archive");
  fs::create_directories(dir / "rec");
  std::ofstream(dir / "rec" / "INDEX.txt") << "d-0.000000-0.pgm\n";
  fs::create_symlink("/etc/hostname", dir / "rec" / "hands.csv");
  ASSERT_EQ(std::system(("tar czf " + (dir / "linked.tar.gz").string() + " -C " + dir.string() + " rec").c_str()), 0);
  EXPECT_NE(errorOf([&] {
              (void)readDepthRecording(dir / "linked.tar.gz");
            }).find("the entry 'rec/hands.csv' is not a regular file"),
            std::string::npos);
  fs::path deep = dir / "deep";
  std::string name;
  for (int k = 0; k < 400; ++k) name += "dd/";  // 1200 bytes
  fs::create_directories(dir / "deep" / name);
  ASSERT_EQ(
      std::system(("tar czf " + (dir / "deep.tar.gz").string() + " -C " + (dir / "deep").string() + " dd").c_str()), 0);
  const std::string message = errorOf([&] { (void)readDepthRecording(dir / "deep.tar.gz"); });
  EXPECT_NE(message.find("bytes, more than 1024 (not a recording)"), std::string::npos) << message;
}

TEST(ShowProof, NumbersOnTheCommandLineAreDecimalFiniteAndWholeWhereTheyCount) {
  const FiniteRange range(0.0, 20.0);
  for (std::string hex : {"0x10", "0x1p-3", "0X1A"})
    EXPECT_NE(range(hex).find("is not a number (written in decimal)"), std::string::npos) << hex;
  EXPECT_EQ(range("1e1"), "");
  const WholeNumber whole(0, 100000);
  std::string text = "1e4";
  EXPECT_EQ(whole(text), "");
  EXPECT_EQ(text, "10000") << "CLI11 is handed the plain digits";
  for (std::string bad : {"0x10", "6.5", "nan", "1e6"}) EXPECT_NE(whole(bad), "") << bad;
  EXPECT_NE(whole(std::string("6.5")).find("'6.5' is not a whole number"), std::string::npos);
  double value = 0;
  EXPECT_EQ(numberProblem("010", value), "");
  EXPECT_EQ(value, 10.0) << "decimal, not octal";
  EXPECT_NE(
      numberProblem(std::string(400, '9'), value).find("'999999999999999999999999...(400 bytes)' is not a finite"),
      std::string::npos);
  EXPECT_TRUE(isPort("65535"));
  for (const char* port : {"0", "65536", "99999", "0x50", "-1", ""}) EXPECT_FALSE(isPort(port)) << port;
}

TEST(ShowProof, AStreamToAPortThatIsNoPortIsRefused) {
  EXPECT_NE(errorOf([] { (void)streamArguments("udp://127.0.0.1:99999", 16, 16); }).find("from 1 to 65535"),
            std::string::npos);
  EXPECT_NE(errorOf([] { (void)streamArguments("srt://host", 16, 16); }).find("from 1 to 65535"), std::string::npos);
  EXPECT_EQ(errorOf([] { (void)streamArguments("udp://127.0.0.1:9000?ttl=2", 16, 16); }), "(no error)");
}

TEST(ShowProof, SighupStopsLikeSigterm) {
  const InterruptCatcher catcher;
  ASSERT_EQ(std::raise(SIGHUP), 0);  // caught: the test process goes on
  EXPECT_EQ(InterruptCatcher::signal(), SIGHUP);
  EXPECT_EQ(InterruptCatcher::exitStatus(0), 129);
  EXPECT_STREQ(signalName(SIGHUP), "SIGHUP");
}

Scene sceneOf(const std::string& text) { return parseScene(text, "s.toml", fs::current_path()); }

TEST(ShowProof, AnExperimentSceneRefusesTheKeysItWouldIgnore) {
  for (const char* key :
       {"duration = 2.0", "burst_at = 1.0", "[tool]\nkind = \"ring\"", "[input]\nsource = \"script:circles\"",
        "[render]\nenabled = true", "[output]\nply_every = 5"}) {
    const std::string message =
        errorOf([&] { (void)sceneOf(std::string("name = \"e\"\nexperiment = \"catenoid\"\n") + key + "\n"); });
    EXPECT_NE(message.find("s.toml:3:"), std::string::npos) << message;
    EXPECT_NE(message.find("does not apply to the physics experiment 'catenoid'"), std::string::npos) << message;
  }
  EXPECT_NO_THROW((void)sceneOf("name = \"e\"\nexperiment = \"catenoid\"\n[params]\ntensionModel = 1\n"));
}

TEST(ShowProof, SceneNumbersTakeAnyWholeFormAndAreNamedAsWritten) {
  const Scene whole =
      sceneOf("name = \"s\"\n[output]\nply_every = 6.0\n[render]\nwidth = 1.6e3\n[params]\nmaxSubsteps = 1e3\n");
  EXPECT_EQ(whole.run.plyEvery, 6);
  EXPECT_EQ(whole.run.render.image.width, 1600);
  EXPECT_EQ(whole.run.params.maxSubsteps, 1000);
  EXPECT_NE(errorOf([] {
              (void)sceneOf("name = \"s\"\n[output]\nply_every = 6.5\n");
            }).find("ply_every in [output] = 6.5 is not a whole number"),
            std::string::npos);
  EXPECT_NE(errorOf([] {
              (void)sceneOf("name = \"s\"\nduration = 3600.0000001\n");
            }).find("duration = 3600.0000001 is out of range [0.001, 3600]"),
            std::string::npos);
  // std::to_string(1e300) is 301 digits and ".000000".
  const std::string huge = errorOf([] { (void)sceneOf("name = \"s\"\n[render]\ncamera = [1e300, 1, 2]\n"); });
  EXPECT_NE(huge.find("camera in [render]: 1e+300 is not a coordinate"), std::string::npos) << huge;
  EXPECT_LT(huge.size(), 200u) << huge;
  // A scene's poke is never for any negative time, as --burst-at's.
  EXPECT_EQ(sceneOf("name = \"s\"\nburst_at = -2\n").run.burstAt, -2.0);
}

TEST(ShowProof, AScenesRelativeInputStaysInItsFolder) {
  const std::string message =
      errorOf([] { (void)sceneOf("name = \"s\"\n[input]\nsource = \"trajectory:../../etc/passwd\"\n"); });
  EXPECT_NE(message.find("input path '../../etc/passwd' leaves the scene's folder"), std::string::npos) << message;
}

TEST(ShowProof, UntrustedNamesAreEscapedInEveryMessage) {
  const std::string scene = errorOf([] { (void)resolveScene("\x1b]0;pwned\x07"); });
  EXPECT_NE(scene.find("unknown scene '\\x1b]0;pwned\\x07'"), std::string::npos) << scene;
  EXPECT_EQ(scene.find('\x1b'), std::string::npos);
  const std::string folder = errorOf([] {
    (void)checkOutputs({{"--out", "/nonexistent\x1b[2J/x", Output::Kind::Folder, ""}});
  });
  EXPECT_EQ(folder.find('\x1b'), std::string::npos) << folder;
  EXPECT_NE(folder.find("\\x1b[2J"), std::string::npos) << folder;
  const std::string rlo = errorOf([] { (void)sceneOf("name = \"show\xe2\x80\xaegnp\"\n"); });
  EXPECT_NE(rlo.find("name = 'show\\u202egnp' holds control characters"), std::string::npos) << rlo;
}

}  // namespace
}  // namespace gb
