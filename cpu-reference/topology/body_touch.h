#pragma once
// The performer's body as a collider for every film. Its depth points, mapped into the world exactly as the hands
// are, are binned in a dense grid over their box; a living film particle within the touch distance of one touches the
// body. Dry skin breaks a soap film at any speed, so a touch starts the hole front of Algorithm 3 there (cause
// "touch"). Wet hands pass through a film: the body pushes the particles it reaches out to the touch distance, and
// only a strike faster than the strike speed bursts it. The hands that hold the wands never burst their own film: the
// film on the wire within the grip radius of either grip is the hand's own and is not tested. A free bubble is
// nobody's: every point of the body touches it, the hands first of all.

#include <array>
#include <optional>
#include <vector>

#include "model/state.h"

namespace gb {

// How the body meets the film.
struct TouchOptions {
  float distance = 0.02f;    // m: a particle this close to a body point touches it (a film particle's half spacing)
  float gripRadius = 0.3f;   // m: the film on the wire this close to a grip is the hand's own, not tested
  float armDistance = 0.1f;  // m: a particle made inside the body touches it once it has been this far from it
  bool wetHands = false;     // the body pushes the film instead of bursting it at a touch
  float strikeSpeed = 1.5f;  // m/s: with wet hands, an approach faster than this still bursts the film
  size_t maxPoints = 20000;  // the body's points are thinned evenly to at most this many
};

// One frame's body: its points in the world and the grips (the hands on the wands).
struct BodyPoints {
  std::vector<Vec3> points;
  std::vector<Vec3> grips;
  double time = 0.0;  // s of run time the depth frame was taken at
};

// A particle that touched the body: where, and how fast the two closed on each other (m/s, along their separation:
// the body's own motion between its frames and the particle's).
struct Touch {
  size_t particle = 0;
  Vec3 position = Vec3::Zero();
  float approachSpeed = 0.0f;
};

// The body's points binned for nearest-point queries: a dense grid of cells `cell` across over the box of the points
// (grown when the box would need more than kMaxCells, so a far-flung cloud costs no more memory), searched in shells
// of cells around the query, nearest first.
class BodyGrid {
 public:
  BodyGrid() = default;
  BodyGrid(const std::vector<Vec3>& points, float cell);
  // The point nearest to x within `reach` of it, or nothing.
  [[nodiscard]] std::optional<Vec3> nearestPoint(const Vec3& x, float reach) const;
  // Its distance from x.
  [[nodiscard]] std::optional<float> nearestWithin(const Vec3& x, float reach) const;
  [[nodiscard]] bool empty() const { return points_.empty(); }
  [[nodiscard]] size_t size() const { return points_.size(); }

  static constexpr size_t kMaxCells = size_t{1} << 22;

 private:
  // The cell of x, from -rings to cells_ + rings - 1 along each axis; false when x lies farther out.
  [[nodiscard]] bool cellOf(const Vec3& x, int rings, std::array<int, 3>& cell) const;
  [[nodiscard]] size_t index(int i, int j, int k) const;
  // The points of the cells `ring` cells from c along the farthest axis (ring 0: c itself).
  template <class Visit>
  void visitShell(const std::array<int, 3>& c, int ring, Visit&& visit) const;

  std::vector<Vec3> points_;         // sorted by cell
  std::vector<uint32_t> cellStart_;  // points_[cellStart_[c], cellStart_[c + 1]) lie in cell c
  Vec3 lower_ = Vec3::Zero();
  float cell_ = 1.0f;
  std::array<int, 3> cells_{0, 0, 0};
};

// The body between its depth frames: the newest frame's grid and the one before, so that how fast the body closed on
// a particle is known without following its points from frame to frame.
class BodyTouch {
 public:
  explicit BodyTouch(TouchOptions options = {}) : options_(options) {}
  // A new depth frame's body: its points thinned to maxPoints and binned, its grips kept.
  void setBody(const BodyPoints& body);
  // Forgets the body (the input lost, a new film dipped where nobody stands).
  void clear();
  [[nodiscard]] bool hasBody() const { return !now_.empty(); }
  [[nodiscard]] size_t points() const { return now_.size(); }
  [[nodiscard]] const TouchOptions& options() const { return options_; }
  // Whether the hands are wet, and the strike that still bursts a film then (Params::wetHands, touchStrikeSpeed).
  void setHands(bool wet, float strikeSpeed) {
    options_.wetHands = wet;
    options_.strikeSpeed = strikeSpeed;
  }

  // The particles of `state` that touch the body now, the fastest first; a particle's approach speed is how much
  // nearer the body came to it over the body's last frame interval plus the particle's own speed towards it.
  // `armed` (one per particle, grown with the film) keeps which particles have been clear of the body: a film made
  // where the body is (hands held at the sides, the film across the hips) passes through it until it is drawn clear,
  // as a wand tip passes through the bubble it let go of; an unarmed particle is armed once it is clear, and only
  // armed particles touch. `onTheWire`: the film hangs on the wands, and its particles within the grip radius of a grip
  // are left out (the hands holding the wands); a free bubble's are all tested.
  [[nodiscard]] std::vector<Touch> touches(const State& state, std::vector<uint8_t>& armed, bool onTheWire) const;
  // With wet hands: moves each touching particle out to the touch distance from the body (along the line from its
  // nearest point) and takes away its velocity into the body. Returns how many it moved.
  size_t push(State& state, const std::vector<Touch>& touching) const;
  // The touch that bursts the film, if any: the fastest touch with dry hands, one faster than strikeSpeed with wet.
  [[nodiscard]] std::optional<Touch> burstingTouch(const std::vector<Touch>& touching) const;

 private:
  // Whether x lies within the grip radius of one of the newest frame's grips.
  [[nodiscard]] bool atGrip(const Vec3& x) const;

  TouchOptions options_;
  BodyGrid now_, before_;
  std::vector<Vec3> grips_;
  double nowTime_ = 0.0, beforeTime_ = 0.0;
};

}  // namespace gb
