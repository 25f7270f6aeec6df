#pragma once
// Built-in wand gestures (Figure 10), given directly in world space: the scripted input of a headless run.
// Hand input from a camera, a recording or a trajectory file arrives through the stabilizer instead.

#include <string>
#include <vector>

#include "model/wire_frame.h"

namespace gb {

// The wand motions of Figure 10: straight (a), left wand circling (b), both circling (c), twisted with
// sudden, growing redirections (d), up and down (e), rising from below (f); and giant, the default
// performance: a fast forward stroke that closes the wands as it ends, blowing and releasing a free bubble.
enum class Gesture { Straight, CircleLeft, Circles, Twisted, UpDown, Rising, Giant };

struct GestureOptions {
  float tipSeparation = 1.0f;  // distance between the wand tips (m)
  float height = 1.6f;         // height of the tips above the floor, y = 0 (m)
  float speed = 0.8f;          // peak wand speed (m/s)
  float start = 0.5f;          // the wands rest this long first, so the new film settles (s)
  float duration = 3.0f;       // length of the stroke (s)
};

// Both wands at time t (s). Every gesture carries both tips along +z, perpendicular to the film, with
// speed speed * sin^2(pi tau / duration) (tau = t - start), so they start and stop smoothly; the others add
// their own motion with the same sin^2 envelope. Velocities are the exact time derivative for straight and
// a central difference (1e-4 s) of the positions for the others.
WandState gestureAt(Gesture gesture, const GestureOptions& options, double t);

Gesture gestureFromName(const std::string& name);  // throws std::invalid_argument naming the choices
std::vector<std::string> gestureNames();

}  // namespace gb
