// The stage table (cpu-reference/stages/stepper.cpp): its barriers against what each stage reads and writes of the
// device's buffers (kernels/shared/device_data.h).
#include "stages/stepper.h"

#include <gtest/gtest.h>

#include <string>

namespace gb {
namespace {

// A stage that reads a buffer an earlier stage wrote, or writes one an earlier stage read or wrote, must have a
// barrier between them (the GPU runs dispatches with no barrier between them in any order). For every combination
// of the conditions the rows run under, over two steps of a batch, no stage meets such a buffer since the last
// barrier.
TEST(StageTable, ABarrierSeparatesEveryStageFromWhatItReadsOrOverwrites) {
  for (int integrator : {0, 1})
    for (int energyBudget : {0, 1})
      for (uint32_t closed : {0u, 1u})
        for (float drainageDt : {0.0f, 0.02f})
          for (int filmFlow : {0, 1}) {
            Params p;
            p.filmFlow = filmFlow;
            p.integrator = integrator;
            p.energyBudget = energyBudget;
            StepUniforms u;
            u.closed = closed;
            u.drainageDt = drainageDt;
            uint32_t written = 0, read = 0;
            std::string since;  // the stages since the last barrier
            for (int step = 0; step < 2; ++step)
              for (const StageSpec& spec : stepStages()) {
                if (!spec.runs(p, u)) continue;
                const std::string when = " (integrator " + std::to_string(integrator) + ", budget " +
                                         std::to_string(energyBudget) + ", closed " + std::to_string(closed) +
                                         ", drainage " + std::to_string(drainageDt) + ", film flow " +
                                         std::to_string(filmFlow) + ")";
                EXPECT_EQ(spec.reads & written, 0u) << spec.name << " reads what" << since << " wrote" << when;
                EXPECT_EQ(spec.writes & (read | written), 0u)
                    << spec.name << " overwrites what" << since << " read or wrote" << when;
                written |= spec.writes;
                read |= spec.reads;
                since += std::string(" ") + spec.name;
                if (spec.barrierAfter) {
                  written = read = 0;
                  since.clear();
                }
              }
          }
}

}  // namespace
}  // namespace gb
