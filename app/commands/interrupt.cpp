#include "app/commands/interrupt.h"

#include <atomic>
#include <csignal>
#include <iterator>

namespace gb {

namespace {

std::atomic<int> gSignal{0};
constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};
constexpr int kCount = static_cast<int>(std::size(kSignals));
struct sigaction gPrevious[kCount];

extern "C" void onStopSignal(int signal) { gSignal.store(signal); }

}  // namespace

InterruptCatcher::InterruptCatcher() {
  gSignal = 0;
  struct sigaction action {};
  action.sa_handler = onStopSignal;
  sigemptyset(&action.sa_mask);
  // SA_RESTART: a write or a wait for the camera goes on after the flag is set. SA_RESETHAND: the second
  // signal gets the default action and kills.
  action.sa_flags = SA_RESTART | SA_RESETHAND;
  for (int k = 0; k < kCount; ++k) sigaction(kSignals[k], &action, &gPrevious[k]);
}

InterruptCatcher::~InterruptCatcher() {
  for (int k = 0; k < kCount; ++k) sigaction(kSignals[k], &gPrevious[k], nullptr);
}

int InterruptCatcher::signal() { return gSignal.load(); }

const char* signalName(int signal) {
  switch (signal) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    case SIGHUP:
      return "SIGHUP";
    default:
      return "a signal";
  }
}

}  // namespace gb
