#pragma once
// A fakenect recording's depth frames read straight from its files, as fast as the disk gives them (fakenect
// plays a recording in real time): for evaluating the hand detector on many recordings at once. A recording is
// a folder (INDEX.txt, d-… depth files, r-… colour images, a-… accelerometer dumps, device.json) or a .tar.gz archive
// holding one such folder; a trajectory CSV named hands.csv beside the frames is its ground truth (docs/formats.md).

#include <filesystem>
#include <string>
#include <vector>

#include "capture/hand_source.h"
#include "capture/kinect_depth.h"

namespace gb {

struct DepthRecording {
  std::string name;                        // the folder's or the archive's name, without .tar.gz
  std::vector<kinect::DepthFrame> frames;  // times from the first depth frame; gravity from the a- entries, colour
                                           // from the r- entries (and device.json)
  std::vector<HandSample> truth;           // hands.csv, when the recording has one (else empty)
};

// Reads a folder (validated as fakenect playback validates it, readFakenectIndex) or a .tar.gz archive of
// one. Throws HandSourceError naming the recording and the problem.
DepthRecording readDepthRecording(const std::filesystem::path& path);

// True for a path the reader takes as an archive (NAME.tar.gz or NAME.tgz).
bool isRecordingArchive(const std::filesystem::path& path);

}  // namespace gb
