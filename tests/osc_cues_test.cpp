// OSC cues in (app/show/osc_cues.h): each cue a show operator sends arrives as its action, in order; a push button let
// go of is no cue; anything else is counted and ignored, never thrown.
#include "app/show/osc_cues.h"

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <lo/lo.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cmath>
#include <string>
#include <vector>

namespace gb {
namespace {

class CueSender {
 public:
  explicit CueSender(int port) : address_(lo_address_new("127.0.0.1", std::to_string(port).c_str())) {}
  ~CueSender() { lo_address_free(address_); }
  CueSender(const CueSender&) = delete;
  CueSender& operator=(const CueSender&) = delete;
  void send(const char* path) { ASSERT_GE(lo_send(address_, path, ""), 0); }
  void sendFloat(const char* path, float value) { ASSERT_GE(lo_send(address_, path, "f", value), 0); }
  void sendInt(const char* path, int value) { ASSERT_GE(lo_send(address_, path, "i", value), 0); }
  void sendString(const char* path, const char* value) { ASSERT_GE(lo_send(address_, path, "s", value), 0); }
  void sendTwo(const char* path) { ASSERT_GE(lo_send(address_, path, "ii", 1, 2), 0); }
  // A UDP packet that is not OSC at all.
  static void sendBytes(int port, const std::string& bytes) {
    const int fd = socket(AF_INET, SOCK_DGRAM, 0);
    ASSERT_GE(fd, 0);
    sockaddr_in to{};
    to.sin_family = AF_INET;
    to.sin_port = htons(static_cast<uint16_t>(port));
    to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    const auto sent = sendto(fd, bytes.data(), bytes.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
    close(fd);
    ASSERT_EQ(sent, static_cast<ssize_t>(bytes.size()));
  }

 private:
  lo_address address_;
};

// Polls until `count` cues came in or two seconds passed (loopback UDP is quick; the margin is for a loaded machine).
std::vector<Cue> pollFor(OscCueReceiver& receiver, size_t count) {
  std::vector<Cue> cues;
  for (int k = 0; k < 200 && cues.size() < count; ++k) {
    for (const Cue& c : receiver.poll()) cues.push_back(c);
    if (cues.size() < count) usleep(10000);
  }
  return cues;
}

TEST(OscCues, EachCueArrivesAsItsActionInOrder) {
  OscCueReceiver receiver(0);
  CueSender sender(receiver.port());
  sender.send("/giantbubble/burst");
  sender.sendFloat("/giantbubble/dip", 1.0f);  // a push button pressed
  sender.sendFloat("/giantbubble/dip", 0.0f);  // and let go of: no cue
  sender.sendInt("/giantbubble/pause", 1);
  sender.sendInt("/giantbubble/pause", 0);
  sender.send("/giantbubble/pause");
  for (const char* path : {"/giantbubble/reset", "/giantbubble/colouring", "/giantbubble/camera",
                           "/giantbubble/fullscreen", "/giantbubble/performer_view", "/giantbubble/quit"})
    sender.send(path);
  const std::vector<Cue> cues = pollFor(receiver, 11);
  const std::vector<CueAction> expected = {CueAction::Burst,         CueAction::Dip,    CueAction::Pause,
                                           CueAction::Pause,         CueAction::Pause,  CueAction::Reset,
                                           CueAction::Colouring,     CueAction::Camera, CueAction::Fullscreen,
                                           CueAction::PerformerView, CueAction::Quit};
  ASSERT_EQ(cues.size(), expected.size());
  for (size_t k = 0; k < cues.size(); ++k) EXPECT_EQ(cues[k].action, expected[k]) << k;
  EXPECT_EQ(cues[2].state, 1);      // pause
  EXPECT_EQ(cues[3].state, 0);      // resume
  EXPECT_EQ(cues[4].state, -1);     // toggle
  EXPECT_EQ(receiver.taken(), 12);  // the let-go dip is a message taken, and no cue
  EXPECT_EQ(receiver.unknown() + receiver.malformed(), 0);
  EXPECT_STREQ(cueName(CueAction::PerformerView), "performer_view");
}

TEST(OscCues, UnknownAndMalformedMessagesAreCountedAndIgnored) {
  OscCueReceiver receiver(0);
  CueSender sender(receiver.port());
  sender.send("/giantbubble/explode");                                       // unknown
  sender.send("/joint");                                                     // unknown: another program's message
  sender.sendString("/giantbubble/burst", "now");                            // malformed: a string argument
  sender.sendTwo("/giantbubble/dip");                                        // malformed: two arguments
  CueSender::sendBytes(receiver.port(), std::string("\x01\x02not osc", 9));  // malformed: not OSC
  sender.send("/giantbubble/burst");                                         // still taken after all that
  const std::vector<Cue> cues = pollFor(receiver, 1);
  ASSERT_EQ(cues.size(), 1u);
  EXPECT_EQ(cues[0].action, CueAction::Burst);
  for (int k = 0; k < 20 && receiver.unknown() + receiver.malformed() < 5; ++k) {
    (void)receiver.poll();
    usleep(10000);
  }
  EXPECT_EQ(receiver.unknown(), 2);
  EXPECT_EQ(receiver.malformed(), 3);
  const std::vector<std::string> messages = receiver.takeMessages();
  ASSERT_EQ(messages.size(), 5u);  // the first kMostReported are said
  EXPECT_NE(messages[0].find("unknown address /giantbubble/explode"), std::string::npos) << messages[0];
  EXPECT_NE(messages[2].find("/giantbubble/burst with arguments 's'"), std::string::npos) << messages[2];
  EXPECT_NE(messages[4].find("further ones are only counted"), std::string::npos) << messages[4];
}

TEST(OscCues, ACueWithANumberThatIsNotFiniteIsIgnored) {
  OscCueReceiver receiver(0);
  CueSender sender(receiver.port());
  sender.sendFloat("/giantbubble/pause", NAN);       // would pause (NaN != 0)
  sender.sendFloat("/giantbubble/pause", INFINITY);  // a number, but no state
  sender.sendFloat("/giantbubble/burst", 1.0f);
  const std::vector<Cue> cues = pollFor(receiver, 1);
  ASSERT_EQ(cues.size(), 1u);
  EXPECT_EQ(cues[0].action, CueAction::Burst);
  EXPECT_EQ(receiver.malformed(), 2);
  const std::vector<std::string> messages = receiver.takeMessages();
  ASSERT_EQ(messages.size(), 2u);
  EXPECT_NE(messages[0].find("/giantbubble/pause with nan: a cue's number is finite"), std::string::npos)
      << messages[0];
}

TEST(OscCues, AFloodIsReadAFewDozenAtATime) {
  OscCueReceiver receiver(0);
  CueSender sender(receiver.port());
  const int sent = OscCueReceiver::kMostPerPoll + 36;
  for (int k = 0; k < sent; ++k) sender.send("/giantbubble/colouring");
  usleep(100000);
  // One poll reads at most kMostPerPoll messages, so a flood cannot hold the show's frame; the rest come next time.
  // (The socket's default buffer keeps a few hundred such small datagrams on loopback: all 100 are there.)
  const size_t first = receiver.poll().size();
  EXPECT_EQ(first, static_cast<size_t>(OscCueReceiver::kMostPerPoll));
  EXPECT_EQ(first + pollFor(receiver, 36).size(), static_cast<size_t>(sent));
}

TEST(OscCues, APortInUseIsNamed) {
  OscCueReceiver first(0);
  try {
    OscCueReceiver second(first.port());
    FAIL() << "a second receiver on port " << first.port() << " was made";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("--osc-in " + std::to_string(first.port()) + ": cannot listen on UDP port"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace gb
