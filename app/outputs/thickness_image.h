#pragma once
// A picture of the film for people: each triangle filled with its corners' thickness colour (blue thin,
// red thick, as the paper's Figure 8), seen from the front (looking along -z, y up) with a depth test,
// written as PNG. Droplets are drawn as white dots. Not the renderer (host/renderer.h): a quick honest look.

#include <filesystem>

#include "model/film.h"
#include "topology/bursting.h"

namespace gb {

struct ImageView {
  int width = 640;
  int height = 480;
  Vec3 center = Vec3(0.0f, 1.2f, 0.0f);  // world point at the image centre (m)
  float metresAcross = 2.4f;             // world width the image spans (m)
  float thinColour = 0.0f;               // thickness shown as pure blue (m)
  float thickColour = 7e-6f;             // thickness shown as pure red (m)
};

// The window of a run's thickness images: the front-view bounding box of every film drawn so far in the run,
// with a margin, so that the film is framed wherever it is (raised, far off, drifting away). The window only
// grows: a sequence of images zooms out when the film reaches for the edge, and never jitters in between.
class ImageFraming {
 public:
  explicit ImageFraming(const ImageView& base = {}) : view_(base) {}
  // The view for this film, after growing the window to take it in (a film without particles changes nothing).
  ImageView frame(const Film& film);

  static constexpr float kMargin = 0.15f;   // of the box's size, on each side
  static constexpr float kSmallest = 1.0f;  // m: the narrowest window, for a film still small

 private:
  ImageView view_;
  Eigen::AlignedBox2f box_;  // empty until a film is seen
};

void writeThicknessImage(const std::filesystem::path& path, const Film& film, const Aerosol& aerosol,
                         const ImageView& view);

}  // namespace gb
