#pragma once
// How the simulation's OpenMP threads wait. libgomp's default lets an idle thread spin for about
// 300,000 iterations before it sleeps; beside another busy process on the same cores (a renderer, lavapipe's
// threads, a camera thread, another program) the spinning threads take the cores the working ones need, and a
// run of 0.4 s took 63.6 s instead of 1.95 s on a busy 2-core machine (docs/performance.md "Threads"). giantbubble
// therefore waits passively by default.
//
// libgomp reads OMP_WAIT_POLICY once, when it is loaded, before main(): so when neither OMP_WAIT_POLICY nor
// GOMP_SPINCOUNT is set, the program sets OMP_WAIT_POLICY=PASSIVE and executes itself again (once; the variable
// is then set). Whoever sets either variable gets exactly what they set.

namespace gb {

// Call first in main(). Returns only when the policy is in place (or the re-exec failed: the program then goes
// on with libgomp's default, which is slower under load, never wrong).
void preferPassiveOpenMpWaiting(char** argv);

}  // namespace gb
