#pragma once
// The sketch backend (backend.cmake): one device, sketch:0, that opens and computes nothing.
#include "compute/backend.hpp"

namespace depthtrack::compute::sketch {

Backend backend();

}  // namespace depthtrack::compute::sketch
