// Scaling a drawn frame up to the size a run writes (app/outputs/image_scale.h), and the drawn scale `run` picks.
#include "app/outputs/image_scale.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include "app/outputs/render_output.h"

namespace gb {
namespace {

TEST(ImageScale, TheSameSizeIsTheSameImage) {
  const std::vector<uint8_t> rgb{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
  EXPECT_EQ(scaleRgb(rgb, 2, 2, 2, 2), rgb);
}

TEST(ImageScale, TwiceTheSizeInterpolatesBetweenPixelCentresAcrossAndDown) {
  // Exact to the rounding of a byte: two pixels 0 and 200 become four, whose centres lie a quarter and three
  // quarters of the way from the first centre to the second on the inner two (50 and 150), and beyond the centres
  // on the outer two, which hold the edge pixels' values. A row and a column alike: the scaling is separable.
  const std::vector<uint8_t> rgb{0, 0, 0, 200, 100, 40};
  const std::vector<uint8_t> expected{0, 0, 0, 50, 25, 10, 150, 75, 30, 200, 100, 40};
  EXPECT_EQ(scaleRgb(rgb, 2, 1, 4, 1), expected);
  EXPECT_EQ(scaleRgb(rgb, 1, 2, 1, 4), expected);
}

TEST(ImageScale, AnEvenColourStaysEvenAtAnyScale) {
  // A flat grey drawn at 0.75 of 960 x 540 and scaled up: every byte 128, none off by rounding.
  const std::vector<uint8_t> grey(3 * 720 * 405, 128);
  const std::vector<uint8_t> up = scaleRgb(grey, 720, 405, 960, 540);
  ASSERT_EQ(up.size(), 3u * 960 * 540);
  for (uint8_t v : up) ASSERT_EQ(v, 128);
}

TEST(ImageScale, AnImageOfTheWrongSizeIsRefused) {
  EXPECT_THROW((void)scaleRgb(std::vector<uint8_t>(11), 2, 2, 4, 4), std::invalid_argument);
  EXPECT_THROW((void)scaleRgb(std::vector<uint8_t>(12), 2, 2, 0, 4), std::invalid_argument);
}

TEST(RenderOutput, ACpuDriverDrawsAtItsDrawnScaleUnlessAsked) {
  // Exact: a choice, not a measurement (docs/rendering.md, "Drawn scale"). A CPU driver pays for its pixels, so it
  // draws at kCpuDrawnScale of the size; a GPU draws the size; --render-scale always wins.
  RenderOutputOptions o;
  EXPECT_FLOAT_EQ(drawnScaleFor(o, "CPU"), kCpuDrawnScale);
  EXPECT_FLOAT_EQ(drawnScaleFor(o, "discrete GPU"), 1.0f);
  o.drawnScale = 0.5f;
  EXPECT_FLOAT_EQ(drawnScaleFor(o, "discrete GPU"), 0.5f);
  o.drawnScale = 1.0f;
  EXPECT_FLOAT_EQ(drawnScaleFor(o, "CPU"), 1.0f);
  RenderOptions image;
  image.width = 960;
  image.height = 540;
  const RenderOptions drawn = drawnImage(image, 0.75f);
  EXPECT_EQ(drawn.width, 720);
  EXPECT_EQ(drawn.height, 405);
  image.width = 20;  // never under the renderer's 16 pixels a side
  EXPECT_EQ(drawnImage(image, 0.25f).width, 16);
}

TEST(RenderOutput, ACpuDriversVideoTakesBroadcastRateUnlessAsked) {
  // Exact: a choice, not a measurement (docs/rendering.md, "Video rate"). At h = 0.02 s a CPU driver draws every
  // second frame (25 frames/s), a GPU every frame; --video-fps always wins, rounded to a whole stride, at least 1.
  RenderOutputOptions o;
  EXPECT_EQ(videoStrideFor(o, "CPU", 0.02), 2);
  EXPECT_EQ(videoStrideFor(o, "discrete GPU", 0.02), 1);
  EXPECT_EQ(videoStrideFor(o, "CPU", 0.04), 1);   // a 25 Hz simulation: every frame
  EXPECT_EQ(videoStrideFor(o, "CPU", 0.005), 8);  // 200 Hz
  o.videoFps = 50;
  EXPECT_EQ(videoStrideFor(o, "CPU", 0.02), 1);
  o.videoFps = 30;  // 50 / 30 rounds to 2: the video plays at 25, real time
  EXPECT_EQ(videoStrideFor(o, "discrete GPU", 0.02), 2);
  o.videoFps = 1000;  // faster than the simulation: every frame
  EXPECT_EQ(videoStrideFor(o, "CPU", 0.02), 1);
}

}  // namespace
}  // namespace gb
