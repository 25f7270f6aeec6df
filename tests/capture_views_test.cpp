// The views a performer looks at after a run: thickness images that frame the film wherever it is,
// and wands.svg with the floor, the camera and the origin and a title that is not cut.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "app/outputs/thickness_image.h"
#include "capture/scripted_gestures.h"
#include "capture/trajectory_plot.h"
#include "model/film.h"

namespace gb {
namespace {

// The film's front-view box in pixels of a view, (x0, y0, x1, y1).
Eigen::Vector4f pixelBox(const Film& film, const ImageView& v) {
  const float scale = static_cast<float>(v.width) / v.metresAcross;
  Eigen::Vector4f box(1e9f, 1e9f, -1e9f, -1e9f);
  for (size_t i = 0; i < film.state.size(); ++i) {
    const Vec3 p = film.state.position.get(i);
    const float x = static_cast<float>(v.width) / 2 + (p.x() - v.center.x()) * scale;
    const float y = static_cast<float>(v.height) / 2 - (p.y() - v.center.y()) * scale;
    box = Eigen::Vector4f(std::min(box[0], x), std::min(box[1], y), std::max(box[2], x), std::max(box[3], y));
  }
  return box;
}

// A film raised 2 m above the scripted rest (wands 3.6 m up), then one far to the side: each is inside its
// image with at least the margin's worth of pixels around it, and the window never shrinks (no jitter).
TEST(ImageFraming, FramesTheFilmWhereverItIsAndOnlyGrows) {
  const Params params;
  WandState wands = gestureAt(Gesture::Straight, GestureOptions{}, 0.0);
  for (Vec3* tip : {&wands.leftPosition, &wands.rightPosition}) tip->y() += 2.0f;
  const Film raised = generateFilm(params, WandTool{}, wands);
  ImageFraming framing;
  const ImageView first = framing.frame(raised);
  const Eigen::Vector4f box = pixelBox(raised, first);
  // Inside by most of the margin: 15% of the larger box side on each side, less for the aspect (2 px slack).
  EXPECT_GT(box[0], 0.1f * static_cast<float>(first.width));
  EXPECT_LT(box[2], 0.9f * static_cast<float>(first.width));
  EXPECT_GT(box[1], 2.0f);
  EXPECT_LT(box[3], static_cast<float>(first.height) - 2.0f);
  // A fixed window (y 0.3-2.1 m) would have missed it: the film's lowest point is above 2.1 m.
  float lowest = 1e9f;
  for (size_t i = 0; i < raised.state.size(); ++i) lowest = std::min(lowest, raised.state.position.y[i]);
  EXPECT_GT(lowest, 2.1f);

  for (Vec3* tip : {&wands.leftPosition, &wands.rightPosition}) tip->x() += 3.0f;
  const Film aside = generateFilm(params, WandTool{}, wands);
  const ImageView second = framing.frame(aside);
  EXPECT_GE(second.metresAcross, first.metresAcross);  // grows only
  for (const Film* film : {&raised, &aside}) {         // both still in view
    const Eigen::Vector4f b = pixelBox(*film, second);
    EXPECT_GE(b[0], 0.0f);
    EXPECT_LE(b[2], static_cast<float>(second.width));
    EXPECT_GE(b[1], 0.0f);
    EXPECT_LE(b[3], static_cast<float>(second.height));
  }
  const ImageView again = framing.frame(raised);  // back where it was: the window stays
  EXPECT_EQ(again.metresAcross, second.metresAcross);
  EXPECT_EQ(again.center, second.center);
  EXPECT_EQ(framing.frame(Film{}).metresAcross, second.metresAcross);  // no film: nothing changes
}

std::string readAll(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The scene panels draw the floor, the origin and the camera; a long title (a run's input with a long path)
// is broken into lines that fit the plot's width instead of running off it.
TEST(TrajectoryPlot, ShowsFloorCameraAndOriginAndKeepsALongTitleWhole) {
  TrajectoryPlot plot;
  const std::string path(150, 'x');
  plot.title = "giantbubble run: fakenect recording /recordings/" + path + "/take (900 depth frames), stabilized";
  for (int i = 0; i < 30; ++i) {
    const float t = static_cast<float>(i) / 30.0f;
    plot.leftWand.emplace_back(-0.5f, 1.6f + 0.2f * t, 0.3f * t);
    plot.rightWand.emplace_back(0.5f, 1.6f, 0.3f * t);
    plot.leftInput.push_back(plot.leftWand.back());
    plot.rightInput.push_back(plot.rightWand.back());
  }
  plot.camera = Vec3(0.0f, 1.3f, 4.0f);
  const std::filesystem::path svg =
      std::filesystem::temp_directory_path() / ("giantbubble_plot_" + std::to_string(::getpid()) + ".svg");
  writeTrajectoryPlot(svg, plot);
  const std::string text = readAll(svg);
  std::filesystem::remove(svg);
  for (const char* label : {">floor<", ">origin<", ">camera<", "scene, front", "scene, top"})
    EXPECT_NE(text.find(label), std::string::npos) << label;
  // Every character of the title is there, over lines of at most 88 characters (a 14 px line of 720 px).
  std::string title;
  size_t lines = 0;
  for (size_t at = text.find("font-size=\"14\">"); at != std::string::npos;
       at = text.find("font-size=\"14\">", at + 1)) {
    const size_t start = at + 15, end = text.find("</text>", start);
    EXPECT_LE(end - start, 88u);
    title += text.substr(start, end - start);
    ++lines;
  }
  EXPECT_EQ(title, plot.title);
  EXPECT_GE(lines, 3u);
}

}  // namespace
}  // namespace gb
