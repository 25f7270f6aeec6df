#pragma once
// `giantbubble bench`: throughput of the full step on each backend for films of several sizes, per-stage
// times, the bytes and floating-point operations the code asks for per particle-step, and the effective
// memory bandwidth next to a STREAM triad measured in the same run.

#include <filesystem>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace gb {

struct BenchOptions {
  std::vector<int> sizes = {10000, 25650, 100000, 1000000};  // particles
  std::vector<std::string> backends = {"cpu", "vulkan"};
  int steps = 64;  // substeps timed per film (batches of 8)
  std::filesystem::path json = "bench.json";
  std::string device;  // Vulkan device request
};

// Adds the `bench` subcommand and its options to the application.
CLI::App* addBenchCommand(CLI::App& app, BenchOptions& options);

int runBenchmark(const BenchOptions& options);

}  // namespace gb
