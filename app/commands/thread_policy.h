#pragma once
// How the simulation's OpenMP threads wait, and how many run. A frame of the default film starts about 28 parallel
// regions (the solver's sweeps, the flow's passes, the contact search, the statistics) and passes about 65 barriers
// in them, at each of which the thread that finishes first waits for the other:
// - A thread that sleeps at once (OMP_WAIT_POLICY=PASSIVE) must be woken by a system call for the next loop: on
//   the default film on two cores that costs about 2.4 ms of an 11.5 ms frame.
// - A thread that spins long (libgomp's OMP_WAIT_POLICY=ACTIVE, or its 300,000-iteration spin) takes the core a
//   working thread needs when another busy process shares the cores: a run of 0.4 s took 63.6 s instead of 1.95 s
//   on a busy 2-core machine (docs/performance.md "Threads").
// giantbubble therefore spins briefly, kOpenMpSpinCount iterations (about 20 us), then sleeps: the quiet default
// film runs about a quarter faster than sleeping at once, beside one busy process about a seventh slower, beside
// two about a seventh faster (docs/performance.md "Threads").
//
// libgomp reads GOMP_SPINCOUNT once, when it is loaded, before main(): so when neither OMP_WAIT_POLICY nor
// GOMP_SPINCOUNT is set, the program sets GOMP_SPINCOUNT and executes itself again (once; the variable is then
// set). Whoever sets either variable gets exactly what they set.

namespace gb {

inline constexpr const char* kOpenMpSpinCount = "2000";

// Call first in main(). Returns only when the policy is in place (or the re-exec failed: the program then goes
// on with libgomp's default, which is slower, never wrong).
void setOpenMpWaiting(char** argv);

// How many OpenMP threads the simulation runs: all of them, or one fewer for each core other processes keep busy. A
// barrier waits for its slowest thread, and a thread that shares its core with another busy process is slow: the
// default film on two cores beside one busy process runs at 60 frames/s on two threads and 72 on one (quiet, 106 and
// 75; docs/performance.md "Threads"). The results do not depend on the count (ThreadPolicy.* checks it).
// The rule, pure: `current` threads of at most `most`, where other processes keep `othersLoad` cores busy. It gives
// one more core away when the load exceeds the cores given away by 0.6, and takes one back when it falls 0.6 below
// them (a core, 0.4 past them), so that a load between does not make it flap; one thread a sample at most.
int threadsBesideLoad(int most, int current, double othersLoad);

// The simulation's threads, updated from the machine's load: call update() before each frame. It samples the load
// of other processes every half second (the first time after a fifth of a second: beside a busy process the first
// frames run on a thread too many until then), the busy time of the cores this process may run on (/proc/stat, its
// affinity) less this process's own (getrusage), and sets omp_set_num_threads when threadsBesideLoad changes its mind.
// Off where OMP_NUM_THREADS is set (whoever sets it gets what they set) or the machine's load cannot be read: all
// threads, always.
class SimulationThreads {
 public:
  SimulationThreads();
  int update();  // the threads now in use

 private:
  struct Sample {
    double wall = 0, machineBusy = 0, own = 0;  // s
  };
  [[nodiscard]] static bool sample(Sample& s);
  int most_ = 1, current_ = 1;
  bool on_ = false, sampled_ = false;  // sampled_: a load was read since the first sample
  Sample last_;
};

}  // namespace gb
