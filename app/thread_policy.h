#pragma once
// How the simulation's OpenMP threads wait. A frame of the default film starts about 28 parallel regions (the
// solver's sweeps, the flow's passes, the contact search, the statistics) and passes about 65 barriers in them, at
// each of which the thread that finishes first waits for the other:
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

}  // namespace gb
