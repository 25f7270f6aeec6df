// Scene files: any text is a Scene or a SceneError naming the problem; anything else (another exception, a
// crash, a sanitizer report) is a bug.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "scene/scene_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    (void)gb::parseScene(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.toml",
                         "/nonexistent-scene-folder");
  } catch (const gb::SceneError&) {
  }
  return 0;
}
