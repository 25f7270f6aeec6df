// The live window's performer view (app/show/performer_view.h, capture/depth_plot.h): the depth plot drawn small for
// the window is the full plot's every other pixel, and V says when there is nothing to show.
#include "app/show/performer_view.h"

#include <gtest/gtest.h>

#include "capture/depth_plot.h"
#include "capture/hand_detector.h"
#include "tests/synthetic_depth.h"

namespace gb {
namespace {

TEST(PerformerView, TheWindowsPlotIsTheFullPlotsEveryOtherPixel) {
  const kinect::DepthFrame frame = test::renderPerformer(test::SyntheticPerformer{});
  const Detection detection = detectHands(frame, DetectionOptions{});
  ASSERT_GT(detection.performerPixels, 0) << "the synthetic performer is found";
  HandSample hands;
  hands.left.measured = true;
  hands.left.position = Vec3d(0.25, 0.05, 2.0);
  const RgbImage full = drawDepthPlot(frame, detection, hands, 1);
  const RgbImage small = drawDepthPlot(frame, detection, hands, PerformerView::kStep);
  ASSERT_EQ(full.width, kinect::kWidth);
  ASSERT_EQ(small.width, kinect::kWidth / 2);
  ASSERT_EQ(small.height, kinect::kHeight / 2);
  // Every pixel the depth sets is the full plot's at (2u, 2v). The rings and crosses are drawn on whichever pixels
  // their outlines fall, so they differ in a few hundred pixels (of 76,800): at most 2% may differ.
  int differ = 0, body = 0;
  for (int v = 0; v < small.height; ++v)
    for (int u = 0; u < small.width; ++u) {
      const uint8_t* a = &small.rgb[3 * (static_cast<size_t>(v) * small.width + u)];
      const uint8_t* b = &full.rgb[3 * (static_cast<size_t>(2 * v) * full.width + 2 * u)];
      differ += a[0] != b[0] || a[1] != b[1] || a[2] != b[2];
      body += a[0] > a[2] + 40;  // the performer in orange
    }
  EXPECT_LT(differ, small.width * small.height / 50);
  EXPECT_GT(body, 1000) << "the body taken for the performer is drawn";
}

TEST(PerformerView, NothingToShowWithoutADepthCamera) {
  PerformerView view;
  view.setWaiting(true);
  EXPECT_FALSE(view.shown());
  EXPECT_NE(view.toggle().find("this input has none"), std::string::npos);
  EXPECT_FALSE(view.shown());
  EXPECT_FALSE(view.update().has_value());
}

}  // namespace
}  // namespace gb
