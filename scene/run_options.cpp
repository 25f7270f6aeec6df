#include "scene/run_options.h"

namespace gb {

std::string InputOptions::spec() const {
  // --gesture comes from the command line only, so it wins over a scene's input (the default scene's too).
  if (!gesture.empty()) return "script:" + gesture;
  return input.empty() ? std::string("script:straight") : input;
}

}  // namespace gb
