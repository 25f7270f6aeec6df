#pragma once
// A depth frame as a picture a performer can set the camera up by: depth in grey (near bright), no reading in
// dark blue, the floor the detector found in green, the body taken for the performer in orange, its centre in
// cyan, every hand the forest found as a small white cross, and the hands the tracker reports (left red, right
// blue) as rings.
// The image is the camera's own view, unmirrored: the performer's left hand appears on the image's right.

#include <filesystem>

#include "capture/hand_detector.h"
#include "capture/kinect_depth.h"
#include "capture/png_image.h"

namespace gb {

// The picture at 1/step of the camera's resolution (every step-th pixel in each direction): 1 for a file, 2 for
// the live window's performer view, drawn several times a second.
RgbImage drawDepthPlot(const kinect::DepthFrame& frame, const Detection& detection, const HandSample& hands,
                       int step = 1);

void writeDepthPlot(const std::filesystem::path& path, const kinect::DepthFrame& frame, const Detection& detection,
                    const HandSample& hands);

}  // namespace gb
