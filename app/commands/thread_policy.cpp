#include "app/commands/thread_policy.h"

#include <omp.h>
#include <sched.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

namespace gb {

namespace {

double steadySeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

void setOpenMpWaiting(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") || std::getenv("GOMP_SPINCOUNT")) return;
  if (setenv("GOMP_SPINCOUNT", kOpenMpSpinCount, 0) != 0) return;
  execv("/proc/self/exe", argv);  // returns only on failure (no /proc): carry on as we are
}

int threadsBesideLoad(int most, int current, double othersLoad) {
  if (!std::isfinite(othersLoad)) return current;
  const int givenAway = most - current;
  if (othersLoad > givenAway + 0.6) return std::max(current - 1, 1);
  if (othersLoad < givenAway - 0.6) return std::min(current + 1, most);
  return current;
}

SimulationThreads::SimulationThreads() : most_(std::max(omp_get_max_threads(), 1)), current_(most_) {
  on_ = std::getenv("OMP_NUM_THREADS") == nullptr && most_ > 1 && sample(last_);
}

bool SimulationThreads::sample(Sample& s) {
  // The lines of /proc/stat of the cores this process may run on (its affinity: a container's cpuset, taskset), each
  // their time in user, nice, system, idle, iowait, irq, softirq and steal, in clock ticks: busy is all but idle and
  // iowait. The other cores of a shared machine are not this process's concern.
  cpu_set_t mine;
  CPU_ZERO(&mine);
  if (sched_getaffinity(0, sizeof mine, &mine) != 0) return false;
  std::ifstream stat("/proc/stat");
  double busyTicks = 0;
  int cores = 0;
  for (std::string line; std::getline(stat, line);) {
    int core = -1;
    double user, nice, system, idle, iowait, irq, softirq, steal;
    if (std::sscanf(line.c_str(), "cpu%d %lf %lf %lf %lf %lf %lf %lf %lf", &core, &user, &nice, &system, &idle, &iowait,
                    &irq, &softirq, &steal) != 9 ||
        core < 0 || core >= CPU_SETSIZE || !CPU_ISSET(core, &mine))
      continue;
    busyTicks += user + nice + system + irq + softirq + steal;
    ++cores;
  }
  const double tick = static_cast<double>(sysconf(_SC_CLK_TCK));
  rusage own{};
  if (cores == 0 || !(tick > 0) || getrusage(RUSAGE_SELF, &own) != 0) return false;
  const auto seconds = [](const timeval& t) {
    return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec);
  };
  s.wall = steadySeconds();
  s.machineBusy = busyTicks / tick;
  s.own = seconds(own.ru_utime) + seconds(own.ru_stime);
  return true;
}

int SimulationThreads::update() {
  if (!on_) return current_;
  // /proc/stat counts in ticks of 10 ms: over a fifth of a second, two cores read a load to about a tenth of a core,
  // well inside the rule's margin of 0.4.
  if (steadySeconds() - last_.wall < (sampled_ ? 0.5 : 0.2)) return current_;
  Sample next;
  if (!sample(next)) return current_;
  const double othersLoad =
      ((next.machineBusy - last_.machineBusy) - (next.own - last_.own)) / (next.wall - last_.wall);
  last_ = next;
  sampled_ = true;
  const int threads = threadsBesideLoad(most_, current_, othersLoad);
  if (threads != current_) omp_set_num_threads(current_ = threads);
  return current_;
}

}  // namespace gb
