#pragma once
// A film driven by wand input frame by frame: Params::implicitSubsteps implicit steps per frame of Params::frameTime
// (one by default), or the explicit integrator's stable substeps; feeds the stepper interpolated wand states, and
// stops with a clear error if the film goes unstable.

#include <array>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <vector>

#include "model/film.h"
#include "stages/cpu_stepper.h"
#include "stages/stepper.h"
#include "topology/body_touch.h"
#include "topology/bursting.h"
#include "topology/collision.h"
#include "topology/device_residency.h"
#include "topology/film_growth.h"
#include "topology/pinch_off.h"

namespace gb {

// Thrown when the state stops being finite or physical; the message says when and where.
class SimulationUnstable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Whole-film diagnostics, in double (CPU only).
struct FrameStats {
  double time = 0;
  size_t particles = 0;
  size_t triangles = 0;
  double area = 0;             // film area (m^2)
  double volume = 0;           // enclosed (bubble) or swept (open film, cone to the frame centre) volume (m^3)
  double kineticEnergy = 0;    // J
  double elasticEnergy = 0;    // the tension's: spring energy of Eq. (3), or filmTensionEnergy (physical model), J
  double potentialEnergy = 0;  // gravity, J, relative to y = 0
  double liquid = 0;           // total liquid volume (m^3)
  double meanThickness = 0;    // m
  double maxSpeed = 0;         // m/s
  double meanAirFlow = 0;      // mean |air| of Eqs. (7)-(8) (m^3/s)
  double solution = 0;         // soap solution left on the wire, in [0, 1] (Section 7)
  size_t droplets = 0;         // aerosol droplets in flight
  double dropletMass = 0;      // kg
};

// Wall time of the last frame's parts (ms): where a frame's time goes (the run's summary, stats.json).
struct FramePhases {
  double step = 0;      // the stepper's substeps and the state brought back from it
  double topology = 0;  // bursting, yield, film growth and pinch-off, with the stepper's reloads
  double contacts = 0;  // the self-collision search for the next frame, handed to the stepper
};

class Simulation {
 public:
  // A new film generated on the tool's wire frame at the given wand state. Without a stepper the CPU
  // reference runs it.
  Simulation(const Params& params, const WandTool& tool, const WandState& wands,
             std::unique_ptr<Stepper> stepper = nullptr);
  // An existing film (e.g. a closed bubble); its wire frame, if any, is taken at `wands`.
  Simulation(const Params& params, Film film, const WandState& wands, std::unique_ptr<Stepper> stepper = nullptr);

  // The stepper holds a pointer to film_: a Simulation stays where it was made.
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  // Advances one frame (Params::frameTime) while the wands move from their last state to `next`, then runs
  // the frame's topology events (bursting, film growth at the wire, pinch-off) and moves the aerosol.
  void advanceFrame(const WandState& next);

  // Pokes the film: a crack opens at particle i now (a performer's finger, a key in the live window).
  void startBurst(size_t particle);
  // The living interior particle highest up: where a poke from above lands.
  [[nodiscard]] size_t topParticle() const;
  // Closes the film into a free bubble now (pinch_off.h); false if it cannot (already closed, torn, or its
  // loop cannot be capped yet). The wand tips are dry sticks: once pulled clear of the free bubble (farther
  // than pinchDistance from it), a tip that touches it (within collisionDistance, or found inside it by its
  // winding number: it went through the film during the frame) bursts it at the particle nearest to the tip. Two-wand
  // films also pinch off by themselves when the tips come within Params::pinchDistance.
  bool pinch();
  // Dips the wands again: a new film on the frame at `wands` (after a burst, or to start over).
  void dip(const WandState& wands);

  // Whether each wand tip (left, right) bursts a free bubble it touches (pinch() disarms both until they are pulled
  // clear): kept by checkpoints of a long run (bench/film_checkpoint.h), which rebuild the Simulation from its film.
  // The performer's body as the film's collider (body_touch.h): a new depth frame's points in the world, and whether a
  // touch bursts the film (dry hands) or pushes it (wet). The film's rules read it each frame; clearBody forgets it.
  void setBody(const BodyPoints& body);
  void clearBody() {
    touch_.clear();
    bodyTime_ = -1.0;
  }
  [[nodiscard]] double bodyTime() const { return bodyTime_; }  // the run time of the body frame it holds (-1: none)
  void setTouchOptions(const TouchOptions& options) { touch_ = BodyTouch(options); }
  // Where the body burst the film and how fast it struck, when it did (the burst's cause is then "touch").
  [[nodiscard]] const std::optional<Touch>& lastTouch() const { return lastTouch_; }
  [[nodiscard]] std::array<bool, 2> wandsArmed() const { return wandArmed_; }
  void setWandsArmed(std::array<bool, 2> armed) { wandArmed_ = armed; }

  [[nodiscard]] const BurstFront& burst() const { return burst_; }
  [[nodiscard]] const Aerosol& aerosol() const { return aerosol_; }
  [[nodiscard]] const TopologyEvents& lastEvents() const { return events_; }
  [[nodiscard]] const FramePhases& lastPhases() const { return phases_; }

  // The film, its state brought back from the stepper's device first where it stayed there (stateStaysOnDevice).
  [[nodiscard]] const Film& film() const {
    pullState();
    return film_;
  }
  [[nodiscard]] Film& film() {
    pullState();
    geometryFresh_ = false;  // the caller may move it
    return film_;
  }
  // The film's particles (living or not) and triangles, always current in host memory: nothing is brought back.
  [[nodiscard]] size_t particleCount() const { return film_.state.size(); }
  [[nodiscard]] size_t triangleCount() const { return film_.topology.triangleCount(); }
  // The film as far as where it is: its topology, which particles live and their positions, the positions brought
  // back alone from the device where the state stayed there (DeviceResidency::storePositions, a tenth of the state).
  // The rest of its state is as it was last brought back: read that through film(). For the renderer's framing and hole
  // rims when it draws the stepper's own buffers in place, and the bubble's centre sent over OSC.
  [[nodiscard]] const Film& filmPositionsOnly() const;
  // Whether a frame on which no rule between steps acts leaves the film's state and contact list on the stepper's
  // device (true, the default), where the stepper checks the film there (DeviceResidency::probeFilm, film_checks.h):
  // the state then comes back only when a rule acts, a topology event fires or something reads film(). False brings it
  // back after every step. A stepper in host memory has nothing to bring back either way.
  void setStateStaysOnDevice(bool stays) { stateStaysOnDevice_ = stays; }
  [[nodiscard]] const Params& params() const { return params_; }
  // New parameters from the next frame on (live show control): the film stays, its geometry and the stepper are
  // loaded again with them. The frame time stays as setFrameTime left it. Throws std::invalid_argument, the
  // simulation unchanged, when they are out of range or the explicit integrator cannot keep the film stable.
  void setParams(const Params& params);
  [[nodiscard]] double time() const { return time_; }
  [[nodiscard]] int substepsPerFrame() const { return substeps_; }
  // The length of the following frames (s), in (0, 0.1]: the live loop takes steps of two frames' time when the
  // machine falls behind the wall clock. The implicit step is stable at any length (the explicit integrator
  // takes as many more substeps); the film's behaviour changes with it (docs/model.md). Contacts are looked for
  // again when the step is the longest yet, and from then on reach as far as it can move the film.
  void setFrameTime(float h);
  // Implicit solver sweeps per step from now on (the live loop lowers them when a frame runs over its
  // budget); 0 returns to Params::solverSweeps.
  void setSolverSweeps(int sweeps) { solverSweeps_ = sweeps; }
  [[nodiscard]] int solverSweeps() const { return solverSweeps_ > 0 ? solverSweeps_ : params_.solverSweeps; }
  [[nodiscard]] float lastPressure() const { return pressure_; }
  // How often the implicit step's energy budget took energy back (energy_budget.h): frames, and the smallest factor
  // it left on the film's wobble (1: never).
  struct BudgetRecord {
    long frames = 0;             // on which the energy budget acted
    float smallestScale = 1.0f;  // its smallest factor on the wobble
    float largestShift = 0.0f;   // the most drift it gave back in one step (m/s)
  };
  [[nodiscard]] const BudgetRecord& energyBudgetRecord() const { return budgetRecord_; }
  // What the frames copied from the stepper's device into host memory (DeviceResidency::readback), each frame with
  // what was copied since the frame before it (the statistics, the outputs and the renderer reading film()), split by
  // whether the frame had a topology event (a burst under way, film growth at the wire, a pinch-off, a merge): the
  // frames without one are those a GPU-resident frame needs no state for. All zero on the CPU backend.
  struct ReadbackRecord {
    long frames = 0;
    long framesWithoutEvent = 0;
    long framesPassed = 0;  // on which the device's checks let the rules between steps pass (film_checks.h)
    // The other frames on which the device checked the film, by the first rule its checks said may act
    // (Simulation::ruleThatMayAct's names).
    std::map<std::string, long> framesHeldByRule;
    // What those frames copied, by the same rule: whole-state read-backs and bytes (the event's kind: a ring at the
    // wire brings back the region it reads, the merges what they choose by, a burst what its front reads, a pinch-off
    // the whole state).
    std::map<std::string, size_t> stateReadbacksHeldByRule;
    std::map<std::string, uint64_t> bytesHeldByRule;
    size_t stateReadbacks = 0;
    uint64_t bytes = 0;
    uint64_t bytesWithoutEvent = 0;
  };
  [[nodiscard]] const ReadbackRecord& readbackRecord() const { return readbackRecord_; }
  [[nodiscard]] Stepper& stepper() { return *stepper_; }
  [[nodiscard]] FrameStats stats();

  // The uniforms of a step of length dt from wand state a to b (exposed for tests and the GPU backend).
  [[nodiscard]] StepUniforms uniformsFor(const WandState& a, const WandState& b, float dt) const;
  // The tool's wire frame for these wand tips, its loop hanging the way the film's loop hangs now (for drawing
  // and for the film's outputs).
  [[nodiscard]] WireFrame wireFrame(const WandState& wands) const { return frameHanging(wands, loopHang()); }

 private:
  [[nodiscard]] Vec3 loopHang() const;
  [[nodiscard]] WireFrame frameHanging(const WandState& wands, const Vec3& hang) const;
  [[nodiscard]] StepUniforms uniformsBetween(const WandState& a, const WandState& b, float dt, const Vec3& hangA,
                                             const Vec3& hangB) const;
  [[nodiscard]] Vec3 loopHangAfter(const WandState& next) const;
  void chooseSubsteps();
  // After the film's mesh or particles changed (growth, a merge, pinch-off, a dip): its geometry, the substeps
  // and the stepper's copy made anew.
  void reloadFilm();
  void growFilm(const WandState& wands, float wandSpeed);
  // The rules of a film no burst is taking (applyRulesBetweenSteps): the rest-length rules, the merges and growth at
  // the wire, each where the state lies. A film whose state stayed on the device brings back the region a ring at
  // the wire reads (wireGrowthRegion), or what the merges' springs found on the device read and the particles they
  // merge.
  void applyRulesOfAnUnbrokenFilm(const WandState& next, float wandSpeed);
  void mergeCrowdedParticlesWhereTheyLie(SpringEnergyAllowance& allowance);
  // What a round of merges reads of the springs it may try, where the state stayed on the device: the positions,
  // thickness and elasticity of their ends and of the ends' one-rings (those not yet in host memory this frame), and
  // their rest lengths where the device changed them.
  void bringBackWhatAMergeRoundReads(std::span<const uint32_t> springs, std::vector<char>& inHostMemory);
  // Where the device cannot find the merges' springs after a round it took (their list outgrew its room): the film
  // comes back whole and the rounds left run on it, then the stepper takes it whole.
  void finishMergesInHostMemory(SpringEnergyAllowance& allowance, int rounds);
  // After a rule changed `region` of a film left on the device and appended particles and springs from the first
  // new ones on: the stepper takes the region and the new ones (Stepper::updateRegion).
  void reloadRegion(const FilmRegion& region, size_t firstParticle, size_t firstSpring);
  // The yield of stretched springs on the stepper's device, or on the film in host memory.
  void yieldStretchedSpringsWhereTheyLie();
  // Whether the checks that held a frame leave its rules on the CPU to a region of the film: the first that may act,
  // besides those the device runs, is a ring at the wire (the tips not together for a pinch-off), the merges, the
  // floor, a crack by thinning or a burst under way.
  [[nodiscard]] bool aRegionServes(const FilmChecks& checks, const WandState& next, float wandSpeed) const;
  // Whether two wand tips are close enough for the open film between them to pinch off (Params::pinchDistance).
  [[nodiscard]] bool tipsTogether(const WandState& wands) const;
  void burstOnHardImpact();
  void burstOnWandTouch();
  // Whether the body is tested against the film this frame: a free bubble always, the film on the wands with
  // Params::touchWireFilm.
  [[nodiscard]] bool bodyTouchesFilm() const;
  void touchByBody();
  void burstOnFloorTouch();
  void updateContacts();
  void checkStable() const;
  // The stepper's device, null for a stepper that steps the film in host memory (Stepper::device).
  [[nodiscard]] DeviceResidency* device() const { return stepper_->device(); }
  // What the device has copied into host memory so far: nothing without one.
  [[nodiscard]] DeviceReadback deviceReadback() const;
  // The film's changed rest lengths, onto the device where the film lives there.
  void updateDeviceRestLengths();
  void recordReadback(long loadsBefore);
  // Whether the frame passes without the state in host memory: the device's checks say that no rule between steps
  // acts but those the device runs itself (the yield, the payout), which it then runs. Updates the tips' arming.
  bool passesOnDevice(const WandState& next, float wandSpeed);
  // The rules between steps on the film in host memory: the stability check, the bursts, the rest-length rules,
  // merges, growth at the wire, pinch-off (the device's yield and payout in their places where it runs them).
  void applyRulesBetweenSteps(const WandState& next, float wandSpeed);
  // The same on a film whose state stayed on the device (aRegionServes): each rule brings back what it reads. The
  // floor's test the positions; a crack by thinning the thickness and area; the burst's front the particles it
  // reaches, their neighbours and the corners of the triangles that die (particlesTheFrontReads); the rest as
  // applyRulesOfAnUnbrokenFilm.
  void applyRulesWhereTheyLie(const WandState& next, float wandSpeed);
  void advanceBurstWhereItLies(const FilmChecks& checks);
  // Whether the burst's front takes a particle this frame: a living one is scheduled by now.
  [[nodiscard]] bool frontReachesThisFrame() const;
  // After the burst shrank the mesh: the stepper takes the new mesh in place, or the whole film where it does not.
  void takeShrunkMesh();
  // The film checks of the rules between steps from the stepper's device (FilmChecks), if it checks there.
  [[nodiscard]] std::optional<FilmChecks> checksOnDevice(bool atPresentPositions);
  // The first rule between steps that may act on the film the device's checks describe, by name ("contraction",
  // "merge", "ring", ...; docs/formats.md lists them): every rule of advanceFrame's (the yield and the payout, which a
  // stepper may run on its device, only with `deviceRules`), each with its thresholds loosened by kFilmCheckMargin.
  // Null means that none acts.
  [[nodiscard]] const char* ruleThatMayAct(const FilmChecks& checks, const WandState& next, float wandSpeed,
                                           bool deviceRules) const;
  // Whether the checks say a particle may touch the floor (burstOnFloorTouch), or be thin enough to crack
  // (crackWhereThin), their thresholds loosened by kFilmCheckMargin.
  [[nodiscard]] bool mayTouchTheFloor(const FilmChecks& checks) const;
  [[nodiscard]] bool mayCrackByThinning(const FilmChecks& checks) const;
  // The same, leaving out the stability check and a burst scheduled or under way.
  [[nodiscard]] const char* ruleBesideTheBurst(const FilmChecks& checks, const WandState& next, float wandSpeed,
                                               bool deviceRules) const;
  // Whether the yield of stretched springs applies to the film: an open film of the spring model with yieldStretch.
  [[nodiscard]] bool yieldApplies() const;
  // Whether the contraction of slack springs applies to the film: a closed film of the spring model.
  [[nodiscard]] bool contractionApplies() const;
  // The contraction (contractSlackSprings) on the film in host memory, or on the stepper's device where it checks the
  // film there; either way within `allowance`, which it spends.
  void contractSlackSpringsWhereTheyLie(SpringEnergyAllowance& allowance);
  // The contraction on the stepper's device, each slack spring the share of the way that the checks' sums give
  // against `allowance`, which it spends; false where the stepper does not run it there.
  bool contractOnDevice(const FilmChecks& checks, SpringEnergyAllowance& allowance);
  // Whether a free bubble's crowded particles merge this frame: every Params::mergeInterval frames of a closed film.
  [[nodiscard]] bool mergeDue() const;
  // Whether the wire pays out film now: its tips draw (kDrawingSpeed), it holds solution, its loop is intact.
  [[nodiscard]] bool payoutApplies(float wandSpeed) const;
  // Brings the state and the contact list back from the stepper's device where they stayed (film(), every rule).
  void pullState() const;

  Params params_;
  // The film. Its state and contact list may stay on the stepper's device after a frame (stateStaysOnDevice); every
  // read of them brings them back first (pullState), also through the const film(): a cache, hence mutable.
  mutable Film film_;
  mutable bool stateOnDevice_ = false;        // film_.state is behind the device's
  mutable bool positionsOnDevice_ = false;    // film_.state.position is behind the device's
  mutable bool contactsOnDevice_ = false;     // film_.topology.contacts is behind the device's
  mutable bool restLengthsOnDevice_ = false;  // film_.topology.restLength is behind the device's (its yield)
  mutable bool refreshOnPull_ = false;        // the statistics refreshed the device's geometry: so does a pull
  // The film in host memory has the geometry of its present positions: reloadFilm made it, and no step has run since.
  // stats() then does not make it again (a growth frame's 7 ms at 100,000 particles).
  bool geometryFresh_ = false;
  bool stateStaysOnDevice_ = true;
  // The checks stats() made of the film the next frame starts from (its impact test), reset by each step.
  std::optional<FilmChecks> checksForNextFrame_;
  // The checks that held this frame for the rules on the CPU (passesOnDevice), of the film as the step left it.
  std::optional<FilmChecks> heldChecks_;
  // The frame was held for rules that a region of the film serves (aRegionServes): its state stays on the device.
  bool heldForARegion_ = false;
  FilmChecks regionChecks_;         // the checks that held it, with what the device's rules then did
  const char* heldRule_ = nullptr;  // the rule that held this frame (ruleThatMayAct's name), null where none did
  std::unique_ptr<Stepper> stepper_;
  BurstFront burst_;
  Aerosol aerosol_;
  TopologyEvents events_;
  FramePhases phases_;
  std::vector<StepUniforms> substepUniforms_;  // one frame's substeps, reused
  WandState wands_;
  std::array<bool, 2> wandArmed_{true, true};  // a tip bursts a free bubble it touches once armed
  BodyTouch touch_;                            // the performer's body as a collider
  double bodyTime_ = -1.0;                     // the run time of the body frame touch_ holds
  std::optional<Touch> lastTouch_;             // the touch that burst the film
  std::vector<uint8_t> touchArmed_;            // per particle: has been clear of the body (BodyTouch::touches)
  double time_ = 0;
  int substeps_ = 1;
  int solverSweeps_ = 0;  // 0: Params::solverSweeps
  float pressure_ = 0;
  float contactHorizon_;                   // the longest step taken (s): what the contact search must reach across
  mutable ContactHistory contactHistory_;  // the last contact list, for the pairs' rest distances (collision.h)
  ContactSearch contactSearch_;
  long stepCount_ = 0;
  BudgetRecord budgetRecord_;
  int framesSinceMerge_ = 0;  // a closed film's frames since its crowded particles last could merge
  ReadbackRecord readbackRecord_;
  DeviceReadback readbackRecorded_;  // the stepper's copies counted up to the last frame's record
  long loads_ = 0;  // reloadFilm and reloadRegion calls: a merge's or a growth's new film on the stepper
};

}  // namespace gb
