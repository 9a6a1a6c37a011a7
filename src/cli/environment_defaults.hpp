#pragma once
// The command's defaults from the environment: the only place DEPTHTRACK_DEVICE and DEPTHTRACK_GL are read
// (the library reads no environment; TrackerConfig::backend and ::gl_path carry the choice).
#include <string>

namespace depthtrack::cli {

// $DEPTHTRACK_DEVICE, or empty when unset (TrackerConfig::backend: reference).
std::string device_from_environment();
// $DEPTHTRACK_GL, or "auto" when unset or empty.
std::string gl_path_from_environment();

}  // namespace depthtrack::cli
