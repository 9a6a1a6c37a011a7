#pragma once
#include <depthtrack/synth.hpp>

namespace depthtrack::synth {

// Throws InputError naming the first impossible value of the configuration.
void validate_config(const SynthConfig& config);

}  // namespace depthtrack::synth
