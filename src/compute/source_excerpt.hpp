#pragma once
// Numbered lines of kernel source for build-error messages, shared by every backend.
#include <string>

namespace depthtrack::compute {

// `count` numbered lines of source ("   12 | text"), centred on `line` (marked with '>') when
// line > 0, else from the top; with a heading that says which lines they are.
std::string numbered_excerpt(const std::string& source, int line, int count = 40);

}  // namespace depthtrack::compute
