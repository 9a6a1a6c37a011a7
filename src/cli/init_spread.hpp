#pragma once
// --init-spread "METRES DEGREES" of track and eval, its default InitialSpread{}'s.
#include <depthtrack/tracker.hpp>
#include <string>

namespace depthtrack::cli {

// InitialSpread{} as --init-spread takes it: "0.01 5".
std::string default_init_spread();
// "METRES DEGREES" as an InitialSpread; InputError naming --init-spread otherwise.
InitialSpread parse_init_spread(const std::string& text);

}  // namespace depthtrack::cli
