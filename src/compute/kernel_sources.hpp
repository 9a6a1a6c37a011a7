#pragma once
// The files under cl/, embedded at build time (cmake/EmbedFiles.cmake).
#include <string>

namespace depthtrack::compute {

// The text of cl/<file> with every `#include "x.h"` replaced by cl/x.h's text (once per file), so
// that a program needs no include path at run time. Throws BackendError for an unknown file.
std::string kernel_source(const std::string& file);

}  // namespace depthtrack::compute
