// OSC show control: events and the bubble's state reach a loopback receiver, in order.
#include "app/outputs/osc_events.h"

#include <gtest/gtest.h>
#include <lo/lo.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "app/commands/run_command.h"

namespace gb {
namespace {

// A liblo server on a free loopback port that records what it receives.
class LoopbackReceiver {
 public:
  LoopbackReceiver() {
    server_ = lo_server_new_with_proto(nullptr, LO_UDP, nullptr);
    lo_server_add_method(server_, "/giantbubble/event", "sd", &LoopbackReceiver::onEvent, this);
    lo_server_add_method(server_, "/giantbubble/bubble", "dffffff", &LoopbackReceiver::onBubble, this);
  }
  ~LoopbackReceiver() { lo_server_free(server_); }
  [[nodiscard]] std::string target() const { return "127.0.0.1:" + std::to_string(lo_server_get_port(server_)); }
  void drain() {
    while (lo_server_recv_noblock(server_, 200) > 0) {
    }
  }
  std::vector<std::string> events;
  std::vector<double> eventTimes;
  int bubbles = 0;

 private:
  static int onEvent(const char*, const char*, lo_arg** argv, int, lo_message, void* self) {
    auto* r = static_cast<LoopbackReceiver*>(self);
    r->events.emplace_back(&argv[0]->s);
    // liblo packs the arguments as OSC does, 4-byte aligned: a double is copied out, not read in place (UBSan).
    double time = 0;
    std::memcpy(&time, argv[1], sizeof time);
    r->eventTimes.push_back(time);
    return 0;
  }
  static int onBubble(const char*, const char*, lo_arg**, int, lo_message, void* self) {
    ++static_cast<LoopbackReceiver*>(self)->bubbles;
    return 0;
  }
  lo_server server_ = nullptr;
};

TEST(OscEvents, MessagesArriveAtALoopbackReceiverInOrder) {
  LoopbackReceiver receiver;
  OscSender sender(receiver.target());
  const std::vector<std::string> sent = {"film_created", "pinched_off", "burst_started", "burst_finished"};
  for (size_t k = 0; k < sent.size(); ++k) ASSERT_TRUE(sender.event(sent[k], 0.5 * static_cast<double>(k)));
  ASSERT_TRUE(sender.bubble(2.0, Vec3(0.0f, 1.5f, 0.2f), 0.6, 0.05, 0.9));
  receiver.drain();
  EXPECT_EQ(receiver.events, sent);
  EXPECT_EQ(receiver.eventTimes, (std::vector<double>{0.0, 0.5, 1.0, 1.5}));
  EXPECT_EQ(receiver.bubbles, 1);
}

TEST(OscEvents, ARunSendsItsEventsInOrder) {
  LoopbackReceiver receiver;
  RunOptions run;
  run.params.particlesAtFullSolution = 400;
  run.duration = 0.5;
  run.burstAt = 0.1;  // a poke: burst_started follows
  run.backend = Backend::Cpu;
  run.progress = false;
  run.plyEvery = run.imageEvery = 0;
  run.outDir = std::filesystem::temp_directory_path() / ("giantbubble_osc_test_" + std::to_string(::getpid()));
  run.osc = receiver.target();
  ASSERT_EQ(runSimulation(run), 0);
  receiver.drain();
  ASSERT_GE(receiver.events.size(), 3u);
  EXPECT_EQ(receiver.events[0], "film_created");
  EXPECT_EQ(receiver.events[1], "poked");
  EXPECT_EQ(receiver.events[2], "burst_started");
  for (size_t k = 1; k < receiver.eventTimes.size(); ++k) EXPECT_LE(receiver.eventTimes[k - 1], receiver.eventTimes[k]);
  EXPECT_EQ(receiver.bubbles, 26) << "one bubble message per frame and one for the new film";
  std::filesystem::remove_all(run.outDir);
}

TEST(OscEvents, ABadTargetIsNamed) {
  EXPECT_THROW(OscSender("no-port"), std::invalid_argument);
  EXPECT_THROW(OscSender("localhost:http"), std::invalid_argument);
}

}  // namespace
}  // namespace gb
