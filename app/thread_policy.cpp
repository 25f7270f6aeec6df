#include "thread_policy.h"

#include <unistd.h>

#include <cstdlib>

namespace gb {

void setOpenMpWaiting(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") || std::getenv("GOMP_SPINCOUNT")) return;
  if (setenv("GOMP_SPINCOUNT", kOpenMpSpinCount, 0) != 0) return;
  execv("/proc/self/exe", argv);  // returns only on failure (no /proc): carry on as we are
}

}  // namespace gb
