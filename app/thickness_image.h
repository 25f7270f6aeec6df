#pragma once
// A picture of the film for people: each triangle filled with its corners' thickness colour (blue thin,
// red thick, as the paper's Figure 8), seen from the front (looking along -z, y up) with a depth test,
// written as PNG. Droplets are drawn as white dots. Not the renderer (issue 5): a quick honest look.

#include <filesystem>

#include "bursting.h"
#include "film.h"

namespace gb {

struct ImageView {
  int width = 640;
  int height = 480;
  Vec3 center = Vec3(0.0f, 1.2f, 0.0f);  // world point at the image centre (m)
  float metresAcross = 2.4f;              // world width the image spans (m)
  float thinColour = 0.0f;                // thickness shown as pure blue (m)
  float thickColour = 7e-6f;              // thickness shown as pure red (m)
};

void writeThicknessImage(const std::filesystem::path& path, const Film& film, const Aerosol& aerosol,
                         const ImageView& view);

}  // namespace gb
