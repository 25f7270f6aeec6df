#include "capture/trajectory_file.h"

#include <charconv>
#include <cmath>
#include <optional>
#include <string>

#include "capture/output_file.h"
#include "capture/untrusted.h"

namespace gb {

namespace {

constexpr const char* kColumns[] = {"t", "left_x", "left_y", "left_z", "right_x", "right_y", "right_z"};
constexpr const char* kHeader = "t,left_x,left_y,left_z,right_x,right_y,right_z";

std::string trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\r"), b = s.find_last_not_of(" \t\r");
  return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}

std::vector<std::string> splitFields(const std::string& line) {
  std::vector<std::string> fields;
  size_t start = 0;
  while (true) {
    const size_t comma = line.find(',', start);
    fields.push_back(trim(line.substr(start, comma == std::string::npos ? std::string::npos : comma - start)));
    if (comma == std::string::npos) return fields;
    start = comma + 1;
  }
}

std::optional<double> number(const std::string& field) {
  double value = 0.0;
  const char* end = field.data() + field.size();
  const auto [ptr, ec] = std::from_chars(field.data(), end, value);
  if (ec != std::errc() || ptr != end || !std::isfinite(value)) return std::nullopt;
  return value;
}

// A row's hand: all three coordinates, none (not measured), or a HandSourceError naming the column.
std::optional<Vec3d> handOf(const std::vector<std::string>& fields, int hand, const std::string& at) {
  const char* name = hand == 0 ? "left" : "right";
  int present = 0;
  Vec3d p;
  for (int k = 0; k < 3; ++k) {
    const std::string& f = fields[1 + 3 * hand + k];
    const char* column = kColumns[1 + 3 * hand + k];
    if (f.empty()) continue;
    const std::optional<double> v = number(f);
    if (!v) throw HandSourceError(at + ": " + column + " '" + printable(f) + "' is not a number");
    if (std::abs(*v) > kMaxHandDistance)
      throw HandSourceError(at + ": " + column + " " + printableNumber(f) + " m is more than " +
                            std::to_string(static_cast<int>(kMaxHandDistance)) +
                            " m from the camera (a trajectory is in metres)");
    p[k] = *v;
    ++present;
  }
  if (present != 0 && present != 3)
    throw HandSourceError(at + ": the " + name + " hand has " + std::to_string(present) +
                          " of 3 coordinates (leave all three empty to mark it missing)");
  if (present && p.z() <= 0.0)  // a camera sees what is in front of it; a stabilizer would divide by it
    throw HandSourceError(at + ": " + kColumns[3 + 3 * hand] + " " + printableNumber(fields[3 + 3 * hand]) +
                          " m puts the " + name + " hand behind the camera (z is the distance in front of it, > 0)");
  return present ? std::optional<Vec3d>(p) : std::nullopt;
}

// The note for the rows from `at` on, which are not read.
std::string unreadRowsNote(const std::string& at, bool pastTheRunsEnd, std::size_t rows) {
  if (pastTheRunsEnd) return "note: " + at + ": past the run's end; the rows from here are not read";
  return "note: " + at + ": " + std::to_string(rows) + " rows read, the most a trajectory may have; the rest is not";
}

}  // namespace

std::vector<HandSample> readTrajectory(const std::filesystem::path& path, double holdTime,
                                       const TrajectoryLimits& limits, std::string* cut) {
  const std::string file = "trajectory file " + printablePath(path);
  std::string why;
  const InputFile in = openInputFile(path, kMaxTrajectoryBytes, why);
  if (!in) throw HandSourceError(file + ": " + why);
  std::vector<HandSample> samples;
  HandHold hold[2] = {HandHold(holdTime), HandHold(holdTime)};
  bool header = false;
  std::optional<double> bothHandsFrom;  // the time of the first row with both hands
  bool pastTheEnd = false;
  std::string line;
  LineRead read = LineRead::Line;
  for (int lineNumber = 1; (read = readLine(in.get(), line, kMaxTrajectoryLineBytes)) != LineRead::End; ++lineNumber) {
    const std::string at = file + ", line " + std::to_string(lineNumber);
    if (read == LineRead::TooLong)
      throw HandSourceError(at + ": longer than " + std::to_string(kMaxTrajectoryLineBytes) +
                            " bytes (a row of seven numbers is under 200)");
    if (lineNumber == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);  // a UTF-8 BOM some editors add
    line = trim(line);
    if (line.empty() || line[0] == '#') continue;
    const std::vector<std::string> fields = splitFields(line);
    if (!header) {
      bool matches = fields.size() == std::size(kColumns);
      for (size_t i = 0; matches && i < fields.size(); ++i) matches = fields[i] == kColumns[i];
      // The line itself is not quoted: a scene naming any file as its trajectory would have its first line printed.
      if (!matches)
        throw HandSourceError(at + ": expected the header '" + kHeader + "'; this line is not it (" +
                              std::to_string(fields.size()) + " fields)");
      header = true;
      continue;
    }
    if (pastTheEnd || samples.size() == limits.rows) {
      if (cut) *cut = unreadRowsNote(at, pastTheEnd, limits.rows);
      break;
    }
    if (fields.size() != std::size(kColumns))
      throw HandSourceError(at + ": " + std::to_string(fields.size()) + " fields, expected 7 (" + kHeader + ")");
    const std::optional<double> t = number(fields[0]);
    if (!t) throw HandSourceError(at + ": time '" + printable(fields[0]) + "' is not a number");
    if (!samples.empty() && *t <= samples.back().time)
      throw HandSourceError(at + ": time " + printableNumber(fields[0]) + " s is not after the previous row's");
    if (!samples.empty() && *t - samples.back().time > kMaxTrajectoryGap) {
      char gap[120];
      std::snprintf(gap, sizeof gap, " s is %.4g s after the previous row's (at most %.0f s between rows)",
                    *t - samples.back().time, kMaxTrajectoryGap);
      throw HandSourceError(at + ": time " + printableNumber(fields[0]) + gap);
    }
    HandSample s;
    s.time = *t;
    for (int h = 0; h < 2; ++h) s.hand(h == 0 ? Hand::Left : Hand::Right) = hold[h].update(*t, handOf(fields, h, at));
    if (!bothHandsFrom && s.left.measured && s.right.measured) bothHandsFrom = *t;
    samples.push_back(s);
    pastTheEnd = bothHandsFrom && *t - *bothHandsFrom > limits.seconds;  // the last row read: the run ends before it
  }
  if (!header) throw HandSourceError(file + ": empty (expected the header '" + std::string(kHeader) + "')");
  if (samples.empty()) throw HandSourceError(file + ": no samples after the header");
  return samples;
}

TrajectoryWriter::TrajectoryWriter(const std::filesystem::path& path) : file_(path, RowFile::Place::AtClose) {
  file_.write("# giantbubble hand trajectory: camera space (x right, y up, z away from the camera), m and s\n" +
              std::string(kHeader) + "\n");
}

void TrajectoryWriter::write(const HandSample& s) {
  char row[160];
  int n = std::snprintf(row, sizeof row, "%.6f", s.time);
  for (const HandObservation* h : {&s.left, &s.right}) {
    if (h->measured)
      n += std::snprintf(row + n, sizeof row - static_cast<size_t>(n), ",%.6f,%.6f,%.6f", h->position.x(),
                         h->position.y(), h->position.z());
    else
      n += std::snprintf(row + n, sizeof row - static_cast<size_t>(n), ",,,");
  }
  n += std::snprintf(row + n, sizeof row - static_cast<size_t>(n), "\n");
  file_.write(std::string_view(row, static_cast<size_t>(n)));  // a full disk stops the recording, naming the file
}

void TrajectoryWriter::close() { file_.close(); }

}  // namespace gb
