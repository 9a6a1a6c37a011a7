#pragma once
// The files under cl/, embedded at build time (cmake/EmbedFiles.cmake).
#include <map>
#include <string>

namespace depthtrack::compute {

// The text of cl/<file> with every `#include "x.h"` replaced by cl/x.h's text (once per file), so
// that a program needs no include path at run time. Throws BackendError for an unknown file.
std::string kernel_source(const std::string& file);

// A backend's kernel-language words (src/compute/<name>/dt_prelude_<name>.h, which depthtrack_compute_backend
// embeds as compute::<name>::prelude_files()), to go before every program's source. It ends in `#line 1`, so
// that the compiler's line numbers are those of the source. Throws BackendError when `file` is not embedded.
std::string program_prelude(const std::map<std::string, std::string>& embedded, const std::string& file);

}  // namespace depthtrack::compute
