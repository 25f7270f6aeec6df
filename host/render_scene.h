#pragma once
// What the renderer draws, built on the CPU: the camera, the opaque props (floor, wands, string) as a
// triangle soup, the droplets, and the environment (the built-in studio or a user's equirectangular image).
// Pure C++ and Eigen; host/renderer.cpp uploads it.

#include <Eigen/Dense>
#include <array>
#include <vector>

#include "model/film.h"
#include "model/wire_frame.h"
#include "topology/bursting.h"

namespace gb {

// An orbiting camera looking at `target` (the live window's mouse turns and zooms it).
struct OrbitCamera {
  Vec3 target = Vec3(0.0f, 1.2f, 0.0f);  // point looked at (m); the default film hangs around here
  float distance = 3.2f;                 // from the target (m)
  float yaw = 0.8f;                      // about the vertical, radians; 0 looks along -z (the front, along the
                                         // default stroke); 0.8: a three-quarter view that sees the bulge side-on
  float pitch = -0.15f;                  // above the horizontal, radians; -0.15: from below, as a photographer
                                         // crouching before the stage sees the film against the wood behind it
  float fovY = 0.75f;                    // vertical field of view, radians

  [[nodiscard]] Vec3 position() const;
  // World -> Vulkan clip space (y down, depth 0 at near .. 1 at far), for an image of this aspect ratio.
  [[nodiscard]] Eigen::Matrix4f viewProjection(float aspect) const;
  // Clip space -> a point along the view ray from the eye (homogeneous; its xyz / w is the ray's direction):
  // the inverse of the projection and the view's turn alone, from yaw, pitch and fovY. Where the camera stands
  // does not enter, so the sky at infinity drawn with it is the same, to the bit, from anywhere.
  [[nodiscard]] Eigen::Matrix4f skyRays(float aspect) const;
};

// A camera that keeps the film framed as it grows and drifts: it looks from the base camera's direction (yaw,
// pitch, field of view; the pitch raised where a film low down would put the eye under minEyeHeight) at the centre of
// the living particles' bounding box, from the distance at which the film's outline on the image spans `heightFraction`
// of the image height (and at most `widthFraction` of its width), both eased towards with time constant `easing` so
// that the picture does not jump when the film changes shape. The centre is led by its own (eased) velocity times
// `easing`, so that a film drifting at a steady speed stays centred instead of trailing the easing's lag (speed x
// easing: 0.85 m at the default stroke's 1.7 m/s).
class FilmFraming {
 public:
  struct Options {
    float heightFraction = 0.55f;  // of the image height the film's outline spans ("about half")
    float widthFraction = 0.8f;    // of the image width it may span at most (a long bag seen side-on)
    float aspect = 16.0f / 9.0f;   // image width / height
    float easing = 0.5f;           // s, time constant of the camera's approach to the framing
    float minDistance = 1.0f;      // m: a tiny film (or a closing one) does not pull the camera into it
    float maxDrift = 5.0f;         // m/s: the centre moving faster in a frame has jumped (a burst, a new film),
                                   // not drifted, and is led only at this speed
    float minEyeHeight = 0.5f;     // m above the ground (y = 0): a camera looking up at a film low down is
                                   // pitched less, never put under the floor
  };
  FilmFraming() = default;
  explicit FilmFraming(const Options& options) : options_(options) {}
  // The camera for this frame, `dt` seconds after the last (the first call frames at once). With no living
  // particle (the film has burst) the camera stays where it was.
  OrbitCamera update(const OrbitCamera& base, const State& film, float dt);

 private:
  // Distance from `centre` along the base camera's direction at which the living particles' outline spans the
  // options' fractions of the image.
  [[nodiscard]] float framingDistance(const OrbitCamera& base, const State& film, const Vec3& centre) const;
  // The base camera's pitch, raised where needed so that the eye, `distance` from `target`, stays minEyeHeight
  // above the ground.
  [[nodiscard]] float pitchAbove(const OrbitCamera& base, const Vec3& target, float distance) const;

  Options options_;
  bool started_ = false;
  Vec3 target_ = Vec3::Zero();
  Vec3 lastCentre_ = Vec3::Zero();
  Vec3 velocity_ = Vec3::Zero();  // of the bounding box's centre, eased (m/s)
  float distance_ = 0.0f;
};

// Floats per vertex of the props mesh: position, normal, albedo, material, tube radius (0: not a tube), padding
// (GB_RENDER_MESH).
inline constexpr int kPropsVertexFloats = 12;

// The ground (y = 0), and when `frame` is given the two wands (sticks held below the tips) and the string loop
// (or the ring and its handle) as tubes, and when `film` is given the rim of any hole torn in it (a bursting
// film), as a triangle soup of kPropsVertexFloats floats per vertex.
std::vector<float> buildProps(const WireFrame* frame, const Film* film = nullptr);

// Edges of the film's hole rims, 2 particle indices each: edges of one triangle only that are not wire edges
// (both ends held by the wire frame). Empty for an intact film or a closed bubble.
std::vector<uint32_t> holeRimEdges(const Film& film);

// The droplets as (x, y, z, opacity): opacity fades over the last third of a droplet's life.
std::vector<float> packDroplets(const Aerosol& aerosol, float lifetime);

// An equirectangular environment: linear RGB radiance, width x height (2:1), row 0 at the zenith, and the
// direction and strength of its key light (the sun, a softbox) that lights the props.
struct EnvironmentImage {
  int width = 0;
  int height = 0;
  std::vector<float> rgb;
  Vec3 keyLight = Vec3(-0.6f, 0.5f, 0.62f).normalized();  // unit, towards the light
  float keyStrength = 0.8f;                               // irradiance on a prop facing it, in radiance units
  // The ground prop fades into the radiance just below the horizon (horizonRadiance) over this distance (m). An
  // image whose ground does not match the floor's needs it short, so that no edge shows where the floor ends;
  // the default sky paints its ground as the floor is lit and keeps clear air's aerial perspective.
  float hazeDistance = 25.0f;
};

// Albedo of the ground prop: weathered concrete paving, 0.30 (concrete 0.10-0.35 in Oke, "Boundary Layer
// Climates", 1987, Table 1.1). Seen from the default camera, which looks up at the film, most of what a film
// reflects is the ground behind the camera, so the floor sets how bright its interference colours are: over
// asphalt (0.16) the bag's most colourful frame has 0.041 of the image in vivid colour, over this floor 0.060
// (docs/rendering.md, "Ground").
Vec3 groundAlbedo();

// Mean radiance of the environment over the upper (y > 0) and lower hemisphere, solid-angle weighted.
std::array<Vec3, 2> hemisphereMeans(const EnvironmentImage& environment);

// Mean radiance of the environment in a thin band just below the horizon (0 to 3 degrees down): the colour
// the far ground fades into.
Vec3 horizonRadiance(const EnvironmentImage& environment);

// The default environment: an outdoor sky, procedural. A blue sky brightening to a pale haze at the horizon,
// scattered clouds, a sun (the key light) behind the default camera's left shoulder with its glow, a line of
// wooded hills on the horizon, the sunlit edge of a wood 30 m behind the stage (straight ahead of the default
// camera, rising to about 30 degrees: the dark backdrop the film is seen against), and below the horizon the
// ground as the floor prop is lit (groundAlbedo under the sky and the sun), so that the floor meets it without a
// seam.
EnvironmentImage skyEnvironment(int width = 1024);

// The built-in studio: a grey-blue room, bright above, dark floor below the horizon, two large softboxes and
// a strip light that the film reflects as coloured highlights.
EnvironmentImage studioEnvironment(int width = 512);

}  // namespace gb
