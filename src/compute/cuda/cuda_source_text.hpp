#pragma once
// Reading kernel source text for messages: kernel names, and numbered lines near an error.
#include <string>

namespace depthtrack::compute::cuda {

// The line of the first "<file>(<line>): error" in an NVRTC log; 0 when there is none.
int first_error_line(const std::string& log);

// `count` numbered lines of source ("  12 | text"), centred on `line` (marked with '>') when
// line > 0, else from the top; with a heading that says which lines they are.
std::string numbered_excerpt(const std::string& source, int line, int count = 40);

}  // namespace depthtrack::compute::cuda
