#pragma once
// `giantbubble record`: reads a hand input and keeps it. From a live camera (or a recording) it writes the raw
// depth as a fakenect recording; from any input it writes the hand trajectory as CSV, plots the input against
// the stabilized wands (SVG), and reports the jitter and lag of both stabilizers.

#include <CLI/CLI.hpp>
#include <string>

#include "app/commands/input_options.h"
#include "capture/scripted_gestures.h"

namespace gb {

struct RecordOptions {
  InputOptions input;
  GestureOptions gesture;
  std::string trajectory;   // CSV of the hands (camera space)
  std::string fakenect;     // folder for a fakenect recording of the depth frames (kinect or fakenect input)
  std::string plot;         // SVG of the input hands against the stabilized wands (world space)
  std::string depthPlot;    // PNG of one depth frame with the hands found in it (kinect or fakenect input)
  int depthPlotFrame = -1;  // which frame (from 0); negative: the last one
  bool report = false;      // print jitter and lag of both stabilizers
  double duration = -1.0;   // seconds; negative: the whole input (a script: its stroke and 0.5 s; kinect: Ctrl-C)
  SourceNoise noise;        // added to a scripted input, to compare the stabilizers against the truth
};

CLI::App* addRecordCommand(CLI::App& app, RecordOptions& options);
int runRecord(const RecordOptions& options);  // the process exit code: 0, 1, or 128 + a signal that ended it

}  // namespace gb
