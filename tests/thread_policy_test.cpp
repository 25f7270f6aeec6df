// How many threads the simulation runs beside other processes' load (app/commands/thread_policy.h).
#include "app/commands/thread_policy.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <limits>

#include "capture/scripted_gestures.h"
#include "scene/scene_file.h"
#include "simulation/simulation.h"

namespace gb {
namespace {

// Two cores: a busy process (a core's load) takes one thread away, a quiet machine gives it back; a load in the band
// between the two thresholds (0.4 to 0.6 cores past those given away) keeps whatever count runs, so a load there
// does not make the count flap.
TEST(ThreadPolicy, ACoreBusyElsewhereTakesAThreadAwayAndAQuietMachineGivesItBack) {
  EXPECT_EQ(threadsBesideLoad(2, 2, 0.05), 2);
  EXPECT_EQ(threadsBesideLoad(2, 2, 1.0), 1);
  EXPECT_EQ(threadsBesideLoad(2, 1, 1.0), 1);
  EXPECT_EQ(threadsBesideLoad(2, 1, 0.05), 2);
  for (const double band : {0.45, 0.5, 0.55}) {
    EXPECT_EQ(threadsBesideLoad(2, 2, band), 2) << band;
    EXPECT_EQ(threadsBesideLoad(2, 1, band), 1) << band;
  }
}

// Sixteen threads beside loads of 0 to 20 cores, one step a sample: at most one thread a step, never fewer than one;
// a load that cannot be measured changes nothing.
TEST(ThreadPolicy, ManyCoresGiveAwayOneThreadAStepAndKeepOne) {
  int threads = 16;
  for (int step = 0; step < 4; ++step) threads = threadsBesideLoad(16, threads, 3.0);
  EXPECT_EQ(threads, 13);
  for (int step = 0; step < 30; ++step) threads = threadsBesideLoad(16, threads, 20.0);
  EXPECT_EQ(threads, 1);
  EXPECT_EQ(threadsBesideLoad(16, 5, std::numeric_limits<double>::quiet_NaN()), 5);
  EXPECT_EQ(threadsBesideLoad(16, 16, -0.2), 16) << "a machine busy less than this process: all of them";
}

// The count may change between frames because the figures do not depend on it: the default performance through
// its growth at the wire and its pinch-off (frame 93) on one thread and on two, every frame's figures equal to the
// last bit.
TEST(ThreadPolicy, TheFilmIsTheSameOnOneThreadAndOnTwo) {
  const Scene scene = resolveScene("default");
  const auto wandsAt = [&](int f) {
    return gestureAt(Gesture::Giant, scene.run.gestureOptions, static_cast<double>(f) * scene.run.params.frameTime);
  };
  Simulation one(scene.run.params, WandTool{}, wandsAt(0)), two(scene.run.params, WandTool{}, wandsAt(0));
  const int most = omp_get_max_threads();
  for (int f = 1; f <= 100; ++f) {
    omp_set_num_threads(1);
    one.advanceFrame(wandsAt(f));
    const FrameStats a = one.stats();
    omp_set_num_threads(2);
    two.advanceFrame(wandsAt(f));
    const FrameStats b = two.stats();
    ASSERT_EQ(a.particles, b.particles) << "frame " << f;
    ASSERT_EQ(a.kineticEnergy, b.kineticEnergy) << "frame " << f;
    ASSERT_EQ(a.elasticEnergy, b.elasticEnergy) << "frame " << f;
    ASSERT_EQ(a.volume, b.volume) << "frame " << f;
    ASSERT_EQ(a.liquid, b.liquid) << "frame " << f;
  }
  omp_set_num_threads(most);
  EXPECT_TRUE(one.film().topology.isClosed()) << "the film pinched off";
}

}  // namespace
}  // namespace gb
