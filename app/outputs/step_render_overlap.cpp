#include "app/outputs/step_render_overlap.h"

#include <algorithm>
#include <cstdio>

#include "host/vulkan_stepper.h"

namespace gb {

namespace {

// The intervals as disjoint ones in time order: overlapping or touching ones joined.
std::vector<Renderer::BusyInterval> joined(std::vector<Renderer::BusyInterval> intervals) {
  std::sort(intervals.begin(), intervals.end(), [](const auto& a, const auto& b) { return a.start < b.start; });
  std::vector<Renderer::BusyInterval> out;
  for (const auto& i : intervals) {
    if (!out.empty() && i.start <= out.back().end)
      out.back().end = std::max(out.back().end, i.end);
    else
      out.push_back(i);
  }
  return out;
}

double lengthOf(const std::vector<Renderer::BusyInterval>& disjoint) {
  double sum = 0;
  for (const auto& i : disjoint) sum += i.end - i.start;
  return sum;
}

// The time two lists of disjoint intervals in time order share.
double sharedTime(const std::vector<Renderer::BusyInterval>& a, const std::vector<Renderer::BusyInterval>& b) {
  double shared = 0;
  for (size_t i = 0, j = 0; i < a.size() && j < b.size();) {
    shared += std::max(0.0, std::min(a[i].end, b[j].end) - std::max(a[i].start, b[j].start));
    if (a[i].end < b[j].end)
      ++i;
    else
      ++j;
  }
  return shared;
}

}  // namespace

void StepRenderOverlap::addStep(double start, double end) {
  if (end >= start) steps_.push_back({start, end});
}

void StepRenderOverlap::addStep(const Stepper& stepper, double start, double end) {
  const auto* vulkan = dynamic_cast<const VulkanStepper*>(&stepper);
  if (const std::optional<Interval> onDevice = vulkan ? vulkan->lastStepOnDevice() : std::nullopt) {
    steps_.push_back(*onDevice);
    return;
  }
  addStep(start, end);
}

void StepRenderOverlap::addRender(const std::vector<Interval>& drawn) {
  renders_.insert(renders_.end(), drawn.begin(), drawn.end());
}

std::string describeOverlap(const StepRenderOverlap::Totals& totals, double wall) {
  if (!totals.renderTimed) return "not timed: the render's device has no timestamps on the host's clock";
  char text[160];
  std::snprintf(text, sizeof text, "%.2f s of %.2f s wall (%.0f%%); step %.2f s, render %.2f s", totals.both, wall,
                wall > 0 ? 100.0 * totals.both / wall : 0.0, totals.step, totals.render);
  return text;
}

double steadySeconds(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(t.time_since_epoch()).count();
}

StepRenderOverlap::Totals StepRenderOverlap::totals() const {
  const std::vector<Interval> steps = joined(steps_), renders = joined(renders_);
  return {lengthOf(steps), lengthOf(renders), sharedTime(steps, renders), !renders_.empty()};
}

}  // namespace gb
