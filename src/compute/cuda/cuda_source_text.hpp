#pragma once
// Reading kernel source text for messages: kernel names, and numbered lines near an error.
#include <string>

#include "compute/source_excerpt.hpp"

namespace depthtrack::compute::cuda {

// The line of the first "<file>(<line>): error" in an NVRTC log; 0 when there is none.
int first_error_line(const std::string& log);

// Numbered lines around it: compute::numbered_excerpt (compute/source_excerpt.hpp).

}  // namespace depthtrack::compute::cuda
