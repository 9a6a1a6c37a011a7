#include "cli/environment_defaults.hpp"

#include <cstdlib>

namespace depthtrack::cli {

std::string device_from_environment() {
  const char* value = std::getenv("DEPTHTRACK_DEVICE");
  return value ? value : "";
}

std::string gl_path_from_environment() {
  const char* value = std::getenv("DEPTHTRACK_GL");
  return value && *value ? value : "auto";
}

}  // namespace depthtrack::cli
