#pragma once
// The known scene of the render tests and of `giantbubble render-reference`: a closed bubble (two overlapping
// sheets from any view, which exercises the order-independent transparency) whose thickness grows from 40 nm
// at the bottom to 1.2 um at the top, so that every interference order shows, held under a two-wand frame, with
// a ring of droplets.

#include <cmath>

#include "host/renderer.h"
#include "model/film.h"
#include "model/params.h"
#include "model/wire_frame.h"
#include "topology/bursting.h"

namespace gb::test {

struct KnownScene {
  Film film;
  Aerosol aerosol;
  WireFrame frame;
  OrbitCamera camera;
};

inline KnownScene makeKnownScene() {
  KnownScene s;
  const Params params;
  s.film = generateSphere(params, Vec3(0.0f, 1.2f, 0.0f), 0.5f, 3);
  State& st = s.film.state;
  for (size_t i = 0; i < st.size(); ++i) {
    const float height = (st.position.y[i] - 0.7f) / 1.0f;  // 0 at the bottom, 1 at the top
    st.thickness[i] = 40e-9f + height * 1.16e-6f;
    st.airFlow.set(i, Vec3(0.0f, 0.0f, 0.02f * height));
  }
  WandState wands;
  wands.leftPosition = Vec3(-0.55f, 1.75f, 0.0f);
  wands.rightPosition = Vec3(0.55f, 1.75f, 0.0f);
  WandTool tool;
  s.frame = makeWireFrame(tool, wands, hangingStringLength(0.55f, 0.3f), Vec3(0.0f, -9.81f, 0.0f));
  for (int k = 0; k < 60; ++k) {
    const float a = 0.1047f * static_cast<float>(k);
    s.aerosol.add(Vec3(0.8f * std::cos(a), 1.2f + 0.8f * std::sin(a), 0.1f), Vec3::Zero(), 1e-9f);
  }
  s.camera.target = Vec3(0.0f, 1.2f, 0.0f);
  s.camera.distance = 2.6f;
  s.camera.yaw = 0.0f;     // from the front
  s.camera.pitch = 0.12f;  // nearly level (the reference image was drawn so)
  return s;
}

inline RenderFrame frameOf(const KnownScene& s) {
  RenderFrame f;
  f.film = &s.film;
  f.aerosol = &s.aerosol;
  f.aerosolLifetime = 1.0f;
  f.wireFrame = &s.frame;
  f.camera = s.camera;
  return f;
}

}  // namespace gb::test
