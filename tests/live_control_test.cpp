// Show control (app/control/): every parameter of the table in the catalog with its group and meaning; a set over
// OSC checked as --param checks it and applied between frames; presets that round-trip every parameter; the
// OSCQuery namespace and its server on the loopback, whose VALUE follows an OSC set.
#include "app/control/live_control.h"

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <lo/lo.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "app/control/control_routes.h"
#include "app/control/control_server.h"
#include "app/control/live_params.h"
#include "app/control/oscquery_namespace.h"
#include "app/control/param_catalog.h"
#include "app/control/presets.h"
#include "app/show/live_show.h"
#include "app/show/osc_cues.h"
#include "capture/scripted_gestures.h"
#include "simulation/simulation.h"
#include "tests/vulkan_test_device.h"

namespace gb {
namespace {

using json = nlohmann::ordered_json;

// The straight gesture's wands at its start, held still.
WandState restingWands() { return gestureAt(Gesture::Straight, GestureOptions{}, 0.0); }

// One HTTP exchange on the loopback: the status code and the body (-1 when nothing came back).
int httpGet(int port, const std::string& request, std::string& body) {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(static_cast<uint16_t>(port));
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (connect(fd, reinterpret_cast<const sockaddr*>(&to), sizeof to) != 0) {
    close(fd);
    return -1;
  }
  (void)!write(fd, request.data(), request.size());
  std::string reply;
  char chunk[4096];
  for (ssize_t n; (n = read(fd, chunk, sizeof chunk)) > 0;) reply.append(chunk, static_cast<size_t>(n));
  close(fd);
  if (reply.rfind("HTTP/1.1 ", 0) != 0) return -1;
  const auto headersEnd = reply.find("\r\n\r\n");
  body = headersEnd == std::string::npos ? "" : reply.substr(headersEnd + 4);
  return std::stoi(reply.substr(9, 3));
}
int get(int port, const std::string& target, std::string& body) {
  return httpGet(port, "GET " + target + " HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n", body);
}

Params smallFilm() {
  Params p;
  p.particlesAtFullSolution = 300;
  return p;
}

TEST(ParamCatalog, EveryParameterHasItsGroupMeaningAndUnit) {
  ASSERT_EQ(paramCatalog().size(), paramFields().size());
  for (const ParamInfo& info : paramCatalog()) {
    SCOPED_TRACE(info.field->name);
    EXPECT_NE(info.group, "Other");
    EXPECT_FALSE(info.description.empty()) << "no row in docs/model.md's parameter table";
    EXPECT_EQ(info.description.find('`'), std::string::npos) << "Markdown code marks left in: " << info.description;
    EXPECT_EQ(" " + info.unit(), std::string(info.field->unit).empty() ? " " : info.field->unit);
  }
  EXPECT_EQ(findParamInfo("airDrag")->group, "Surface tension and elasticity");
  EXPECT_EQ(findParamInfo("airPressureGain")->group, "Air");
  EXPECT_EQ(findParamInfo("particlesAtFullSolution")->timing, ParamTiming::NextFilm);
  EXPECT_EQ(findParamInfo("frameTime")->timing, ParamTiming::Start);
}

TEST(LiveParams, SetsAreCheckedAsParamChecksThem) {
  Params wanted;
  LiveParams live(wanted);
  bool refused = true;
  EXPECT_EQ(live.set("airDrag", 2.5, refused), "param airDrag = 2.5");
  EXPECT_FALSE(refused);
  EXPECT_FLOAT_EQ(wanted.airDrag, 2.5f);
  // The refusal is --param's own message.
  Params copy;
  std::string expected;
  try {
    setParameter(copy, "airDrag", 1000.0);
  } catch (const std::invalid_argument& e) {
    expected = e.what();
  }
  EXPECT_EQ(live.set("airDrag", 1000.0, refused), "param airDrag refused: " + expected);
  EXPECT_TRUE(refused);
  EXPECT_FLOAT_EQ(wanted.airDrag, 2.5f);
  EXPECT_NE(live.set("noSuchParameter", 1.0, refused).find("unknown parameter 'noSuchParameter'"), std::string::npos);
  EXPECT_NE(live.set("solverSweeps", 2.5, refused).find("must be a whole number"), std::string::npos);
  EXPECT_NE(live.set("frameTime", 0.01, refused).find("fixed when the show starts"), std::string::npos);
  EXPECT_NE(live.set("airDrag", std::nan(""), refused).find("out of range"), std::string::npos);
  EXPECT_EQ(live.accepted(), 1);
  EXPECT_EQ(live.refused(), 5);
}

TEST(LiveParams, ReachTheSimulationBetweenFramesAndTheNextFilmAtItsDip) {
  Params wanted = smallFilm();
  Simulation sim(wanted, WandTool{}, restingWands());
  LiveParams live(wanted);
  bool refused = false;
  EXPECT_NE(live.set("particlesAtFullSolution", 600, refused).find("takes effect at the next dip"), std::string::npos);
  live.set("surfaceTension", 0.04, refused);
  EXPECT_TRUE(live.apply(sim).empty());
  EXPECT_FLOAT_EQ(sim.params().surfaceTension, 0.04f);
  EXPECT_EQ(sim.params().particlesAtFullSolution, 300);  // the film on stage keeps its size
  sim.advanceFrame(restingWands());
  const size_t before = sim.particleCount();
  EXPECT_TRUE(live.beforeDip(sim).empty());
  sim.dip(restingWands());
  EXPECT_EQ(sim.params().particlesAtFullSolution, 600);
  EXPECT_GT(sim.particleCount(), before * 3 / 2) << "the new film has the new size (about twice the particles)";
}

// A film on resting wands, 10 frames; then gravity turned upwards (or not); the fastest particle 10 frames later.
double fastestAfterGravityUp(std::unique_ptr<Stepper> stepper, bool turned) {
  Params wanted = smallFilm();
  Simulation sim(wanted, WandTool{}, restingWands(), std::move(stepper));
  LiveParams live(wanted);
  for (int k = 0; k < 10; ++k) sim.advanceFrame(restingWands());
  bool refused = false;
  if (turned) live.set("gravityY", 60.0, refused);
  EXPECT_TRUE(live.apply(sim).empty());
  for (int k = 0; k < 10; ++k) sim.advanceFrame(restingWands());
  return sim.stats().maxSpeed;
}

// A set changes the running simulation on either backend: gravity turned up (6 g) at least doubles the film's
// fastest speed within 0.2 s (a film hanging at rest moves at a few cm/s; lifted, at metres per second).
TEST(LiveParams, ASetShowsInTheStatsOnBothBackends) {
  const double cpuStill = fastestAfterGravityUp(nullptr, false), cpuTurned = fastestAfterGravityUp(nullptr, true);
  std::printf("CPU: fastest %.3f m/s, %.3f m/s with gravity turned up\n", cpuStill, cpuTurned);
  EXPECT_GT(cpuTurned, 2.0 * cpuStill + 0.05);
  GB_REQUIRE_VULKAN(device);
  const double gpuStill = fastestAfterGravityUp(std::make_unique<VulkanStepper>(device), false);
  const double gpuTurned = fastestAfterGravityUp(std::make_unique<VulkanStepper>(device), true);
  std::printf("Vulkan: fastest %.3f m/s, %.3f m/s with gravity turned up\n", gpuStill, gpuTurned);
  EXPECT_GT(gpuTurned, 2.0 * gpuStill + 0.05);
}

TEST(Presets, SaveAndRecallRoundTripEveryParameter) {
  const auto dir = std::filesystem::temp_directory_path() / ("gb_presets_" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  PresetLibrary presets(dir);
  Params p;
  // Every parameter off its default, inside its range: two thirds of the way, integers rounded.
  for (const ParamField& f : paramFields()) {
    const double value = f.lo + (f.hi - f.lo) * 0.6789;
    setParameter(p, f.name, f.integer ? std::floor(value) : value);
  }
  presets.save("gentle-opening", p);
  EXPECT_EQ(presets.names(), std::vector<std::string>{"gentle-opening"});
  std::vector<std::string> listed;
  const Params back = presets.load("gentle-opening", &listed);
  for (const ParamField& f : paramFields()) EXPECT_EQ(paramValue(back, f), paramValue(p, f)) << f.name;
  EXPECT_EQ(listed.size(), paramFields().size());
  EXPECT_THROW(presets.save("../escape", p), std::invalid_argument);
  EXPECT_THROW((void)presets.load("missing"), std::exception);
  std::filesystem::remove_all(dir);
}

TEST(OscQueryNamespace, ListsEveryParameterWithRangeUnitAndValue) {
  ControlState state;
  Params p;
  p.airDrag = 3.0f;
  state.params.set(p);
  const json root = oscQueryNamespace(state);
  for (const ParamField& f : paramFields()) {
    const json* node = oscQueryNode(root, std::string("/giantbubble/param/") + f.name);
    ASSERT_NE(node, nullptr) << f.name;
    EXPECT_EQ((*node)["RANGE"][0]["MIN"].get<double>(), f.lo);
    EXPECT_EQ((*node)["RANGE"][0]["MAX"].get<double>(), f.hi);
    EXPECT_EQ((*node)["TYPE"], f.integer ? "i" : "f");
    ASSERT_TRUE((*node)["UNIT"].is_array());
  }
  EXPECT_FLOAT_EQ((*oscQueryValue(root, "/giantbubble/param/airDrag"))[0].get<float>(), 3.0f);
  EXPECT_EQ((*oscQueryNode(root, "/giantbubble/burst"))["ACCESS"], 2);
  EXPECT_NE(oscQueryNode(root, "/giantbubble/status/fps"), nullptr);
  EXPECT_EQ(oscQueryNode(root, "/giantbubble/nothing"), nullptr);
  EXPECT_EQ(oscQueryNode(root, "giantbubble"), nullptr);
  EXPECT_EQ(oscQueryHostInfo(9000)["OSC_PORT"], 9000);
}

TEST(ControlServer, ValueFollowsAnOscSetAndBadRequestsAreRefused) {
  OscCueReceiver receiver(0);
  Params wanted = smallFilm();
  ControlOptions options;
  options.port = 0;  // the command line takes 1..65535; the server takes 0 as any free port
  const auto dir = std::filesystem::temp_directory_path() / ("gb_presets_srv_" + std::to_string(getpid()));
  options.presets = dir.string();
  LiveControl control(options, wanted, receiver);
  // The port from the description "control page at http://127.0.0.1:PORT/control, ...".
  const std::string where = control.describe();
  const auto colon = where.find(':', where.find("127.0.0.1"));
  ASSERT_NE(colon, std::string::npos) << where;
  const int port = std::stoi(where.substr(colon + 1));
  std::string body;
  ASSERT_EQ(get(port, "/", body), 200);
  EXPECT_EQ(json::parse(body)["CONTENTS"]["giantbubble"]["CONTENTS"]["param"]["CONTENTS"].size(), paramFields().size());
  ASSERT_EQ(get(port, "/?HOST_INFO", body), 200);
  EXPECT_EQ(json::parse(body)["OSC_PORT"], receiver.port());
  ASSERT_EQ(get(port, "/control", body), 200);
  EXPECT_NE(body.find("<title>giantbubble control</title>"), std::string::npos);

  Simulation sim(wanted, WandTool{}, restingWands());
  lo_address to = lo_address_new("127.0.0.1", std::to_string(receiver.port()).c_str());
  const auto sent = std::chrono::steady_clock::now();
  lo_send(to, "/giantbubble/param/airDrag", "f", 7.5f);
  lo_send(to, "/giantbubble/param/airDrag", "f", 500.0f);  // out of range: refused
  std::vector<std::string> reports;
  for (int k = 0; k < 200 && reports.size() < 2; ++k) {
    receiver.poll();
    control.betweenFrames(sim, [&](const std::string& what) { reports.push_back(what); });
    if (reports.size() < 2) usleep(10000);
  }
  lo_address_free(to);
  ASSERT_EQ(reports.size(), 2u);
  EXPECT_EQ(reports[0], "param airDrag = 7.5");
  EXPECT_NE(reports[1].find("refused: parameter airDrag = 500 is out of range"), std::string::npos);
  EXPECT_FLOAT_EQ(sim.params().airDrag, 7.5f);
  ASSERT_EQ(get(port, "/giantbubble/param/airDrag?VALUE", body), 200);
  EXPECT_FLOAT_EQ(json::parse(body)["VALUE"][0].get<float>(), 7.5f);
  std::printf("an OSC set to its VALUE over HTTP: %.2f ms\n",
              std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - sent).count());

  EXPECT_EQ(get(port, "/giantbubble/nothing", body), 404);
  EXPECT_EQ(httpGet(port, "POST / HTTP/1.1\r\nHost: x\r\nContent-Length: 2\r\nConnection: close\r\n\r\n{}", body), 405);
  const int garbage = httpGet(port, "NOT HTTP AT ALL\r\n\r\n", body);
  EXPECT_TRUE(garbage == -1 || (garbage >= 400 && garbage < 500)) << garbage;
  EXPECT_EQ(get(port, "/", body), 200) << "the server still answers";
  std::filesystem::remove_all(dir);
}

TEST(LiveControl, AGetIsAnsweredToTheSender) {
  OscCueReceiver receiver(0);
  Params wanted;
  wanted.sticky = 21.5f;
  LiveControl control(ControlOptions{}, wanted, receiver);  // no --control: OSC only
  EXPECT_EQ(control.describe(), "");
  lo_server asker = lo_server_new(nullptr, nullptr);
  ASSERT_NE(asker, nullptr);
  float answer = -1;
  lo_server_add_method(
      asker, "/giantbubble/param/sticky", "f",
      [](const char*, const char*, lo_arg** argv, int, lo_message, void* data) {
        *static_cast<float*>(data) = argv[0]->f;
        return 0;
      },
      &answer);
  lo_address to = lo_address_new("127.0.0.1", std::to_string(receiver.port()).c_str());
  lo_send_from(to, asker, LO_TT_IMMEDIATE, "/giantbubble/param/sticky", "");
  for (int k = 0; k < 200 && answer < 0; ++k) {
    receiver.poll();
    lo_server_recv_noblock(asker, 10);
  }
  lo_address_free(to);
  lo_server_free(asker);
  EXPECT_FLOAT_EQ(answer, 21.5f);
}

TEST(LiveControl, TheDigitKeysRecallPresetsByNumber) {
  std::string why;
  const auto press = parseKeyPress("30:1", why);
  ASSERT_TRUE(press);
  EXPECT_EQ(press->key, '1');
  EXPECT_FALSE(parseKeyPress("30:0", why));
  EXPECT_FALSE(parseKeyPress("30:t", why));  // a letter of the message is no key
  EXPECT_NE(why.find("or a digit 1-9 (a preset)"), std::string::npos) << why;
}

TEST(ControlServer, RefusesAnOpenBindWithoutAToken) {
  ControlRoutes routes;
  EXPECT_THROW(ControlServer({0, "0.0.0.0", "", 0}, routes), std::runtime_error);
  EXPECT_THROW(ControlServer({0, "not-an-address", "t", 0}, routes), std::runtime_error);
}

}  // namespace
}  // namespace gb
