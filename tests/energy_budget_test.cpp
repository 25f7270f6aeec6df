// The implicit step's energy budget (cpu-reference/energy_budget.h): its formulas, and a step that would give a film
// energy nobody put in.
#include "energy_budget.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "cpu_stepper.h"
#include "simulation.h"
#include "test_films.h"

namespace gb {
namespace {

TEST(EnergyBudget, TheGasChangeIsTheDifferenceOfBoylesEnergy) {
  // Against the gas energy itself in double, from the same float volumes. The float difference keeps every case
  // to 1e-4 of the change: the first-order term is the excess pressure's work, exact to a few ulps.
  const Params p;
  const struct {
    float reference, before, after;
  } cases[] = {{0.3f, 0.3f, 0.30001f}, {0.3f, 0.2994f, 0.2995f}, {0.3f, 0.31f, 0.305f},
               {0.3f, 0.25f, 0.28f},   {1.0f, 0.9f, 1.2f},       {0.3f, 0.3f, 0.2f}};
  for (const auto& c : cases) {
    const double exact = boyleGasEnergy(p, c.reference, c.after) - boyleGasEnergy(p, c.reference, c.before);
    const double change = boyleEnergyChange(p, c.reference, c.before, c.after);
    std::printf("V0 %.4f: %.5f -> %.5f m^3, gas energy change %.6e J (double %.6e)\n", c.reference, c.before, c.after,
                change, exact);
    EXPECT_NEAR(change, exact, 1e-4 * std::abs(exact) + 1e-12);
  }
  EXPECT_EQ(boyleEnergyChange(p, 0.3f, 0.0f, 0.3f), 0.0f) << "no volume: no gas to count";
}

TEST(EnergyBudget, TakesTheExcessFromTheMotionAboutTheCentreOfMass) {
  // Three particles of different masses drifting together and apart: the budget must end at exactly the budget
  // (to float rounding, 1e-5), keep the momentum, and leave velocities within the budget untouched.
  const float masses[] = {1.0f, 2.0f, 0.5f};
  const Vec3 velocities[] = {{1.0f, 0.5f, 0.0f}, {0.2f, -0.3f, 0.1f}, {-1.0f, 0.0f, 2.0f}};
  float mass = 0.0f, kinetic = 0.0f;
  Vec3 momentum = Vec3::Zero();
  for (int k = 0; k < 3; ++k) {
    mass += masses[k];
    momentum += masses[k] * velocities[k];
    kinetic += 0.5f * masses[k] * velocities[k].squaredNorm();
  }
  const float held = 1.0f, start = held + 0.6f * kinetic;  // 40% of the kinetic energy was never paid for
  const VelocityBudget budget = energyBudget(start, kinetic, held, mass, momentum);
  float kineticAfter = 0.0f;
  Vec3 momentumAfter = Vec3::Zero();
  for (int k = 0; k < 3; ++k) {
    const Vec3 v = budgetedVelocity(budget, velocities[k]);
    kineticAfter += 0.5f * masses[k] * v.squaredNorm();
    momentumAfter += masses[k] * v;
  }
  std::printf("scale %.4f: kinetic %.4f -> %.4f J against a budget of %.4f J\n", budget.scale, kinetic, kineticAfter,
              start * (1 + kEnergyBudgetTolerance) - held);
  EXPECT_LT(budget.scale, 1.0f);
  EXPECT_NEAR(kineticAfter + held, start * (1 + kEnergyBudgetTolerance), 1e-5 * start);
  EXPECT_LT((momentumAfter - momentum).norm(), 1e-5 * momentum.norm());

  // A step that was not even owed its drift (start below held + drift): no wobble left, the centre slowed so that
  // the kinetic energy is what the budget has left.
  const float drift = 0.5f * momentum.squaredNorm() / mass, poor = held + 0.5f * drift;
  const VelocityBudget slowed = energyBudget(poor, kinetic, held, mass, momentum);
  const Vec3 v = budgetedVelocity(slowed, velocities[0]);
  EXPECT_EQ(slowed.scale, 0.0f);
  EXPECT_EQ(v, budgetedVelocity(slowed, velocities[1])) << "every particle moves with the centre";
  EXPECT_NEAR(0.5f * mass * v.squaredNorm() + held, poor * (1 + kEnergyBudgetTolerance), 1e-5 * poor);

  const VelocityBudget within = energyBudget(held + kinetic, kinetic, held, mass, momentum);
  EXPECT_EQ(within.scale, 1.0f);
  EXPECT_EQ(budgetedVelocity(within, velocities[2]), velocities[2]) << "a step within its budget is left alone";
  EXPECT_EQ(energyBudget(NAN, kinetic, held, mass, momentum).scale, 1.0f) << "non-finite sums are not the budget's";
}

// The film's mechanical energy as the budget defines it, in double and written independently of the stage (springs
// by their ends, contacts once per pair): the kinetic energy of the free particles at velocities v(i), the springs
// and contacts at positions x(i), less the explicit forces' work when `work` is set.
template <class At, class Velocity>
double mechanicalEnergy(const Params& p, const Film& film, At x, Velocity v) {
  const State& s = film.state;
  const Topology& topo = film.topology;
  double sum = 0;
  for (size_t k = 0; k < topo.springCount(); ++k) {
    const uint32_t a = topo.springEnds[2 * k], b = topo.springEnds[2 * k + 1];
    const double stretch = (x(a) - x(b)).norm() - topo.restLength[k];
    sum += 0.25 * (s.elasticity[a] + s.elasticity[b]) * stretch * stretch;
  }
  const size_t base = s.size() + 1;
  for (uint32_t i = 0; i < s.size(); ++i)
    for (uint32_t k = topo.contacts[i]; k < topo.contacts[i + 1]; ++k) {
      const uint32_t j = topo.contacts[base + k];
      const double len = (x(i) - x(j)).norm(), rest = contactRestDistance(topo.contacts, s.size(), k);
      if (j > i && len < rest) sum += 0.5 * p.collisionStiffness * (rest - len) * (rest - len);
    }
  for (size_t i = 0; i < s.size(); ++i)
    if (s.alive[i] && !topo.boundary[i]) sum += 0.5 * s.mass[i] * v(i).squaredNorm();
  return sum;
}

struct SpunStep {
  double before = 0, after = 0, work = 0;
  float scale = 1;
};

// A free disc (a ring's film with its rim let go) spun about its normal at `spin` rad/s and stepped once with a
// single sweep: the first guess x_t + h v_t turns the disc and stretches it by sqrt(1 + (h spin)^2), and one sweep
// cannot pull it back, so the unbudgeted step ends with more energy than it started with.
SpunStep spinAndStep(int energyBudget, float rate) {
  Params p;
  p.particlesAtFullSolution = 1000;
  p.solverIterations = 1;
  p.energyBudget = energyBudget;
  Film disc = test::makeFreeDisc(p);
  test::spin(disc, disc.state.normal.get(0), rate);
  Simulation sim(p, disc, WandState{});
  Film film = sim.film();
  State& s = film.state;
  const StepUniforms u = sim.uniformsFor(WandState{}, WandState{}, p.frameTime);
  CpuStepper stepper;
  stepper.load(p, film);
  SpunStep r;
  const auto position = [&](size_t i) -> Eigen::Vector3d { return s.position.get(i).cast<double>(); };
  const auto velocity = [&](size_t i) -> Eigen::Vector3d { return s.velocity.get(i).cast<double>(); };
  for (const StageSpec& spec : stepStages()) {
    if (!spec.runs(p, u)) continue;
    if (spec.stage == Stage::ImplicitPredict) r.before = mechanicalEnergy(p, film, position, velocity);  // x_t, v_t
    const float result = stepper.runStage(spec.stage, u);
    if (spec.stage == Stage::EnergyBudget) r.scale = result;
  }
  r.after = mechanicalEnergy(p, film, position, velocity);
  for (size_t i = 0; i < s.size(); ++i)
    if (s.alive[i])
      r.work += s.force.get(i).cast<double>().dot((position(i) - s.previousPosition.get(i).cast<double>()));
  return r;
}

TEST(EnergyBudget, AStepNeverEndsAboveItsBudget) {
  const SpunStep free = spinAndStep(0, 12.0f), budgeted = spinAndStep(1, 12.0f);
  std::printf(
      "disc spun at 12 rad/s, one sweep: %.5f J + work %.5f J -> %.5f J unbudgeted, %.5f J budgeted (scale %.4f)\n",
      free.before, free.work, free.after, budgeted.after, budgeted.scale);
  // The unbudgeted step must break the budget for this test to mean anything (it gains 10%).
  EXPECT_GT(free.after, (free.before + free.work) * 1.05);
  // The budgeted one ends at its budget: the tolerance, plus 1e-5 for the float sums against this double count.
  EXPECT_LT(budgeted.scale, 1.0f);
  EXPECT_LE(budgeted.after, (budgeted.before + budgeted.work) * (1 + kEnergyBudgetTolerance + 1e-5));
}

}  // namespace
}  // namespace gb
