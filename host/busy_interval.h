#pragma once
// When the device ran a submission's commands, first to last, in seconds of the host's steady clock
// (std::chrono::steady_clock; VulkanContext::busyInterval reads them from the device's timestamps).

namespace gb {

struct DeviceBusyInterval {
  double start = 0, end = 0;
};

}  // namespace gb
