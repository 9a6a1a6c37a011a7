#pragma once
// Every frame of a synthetic sequence in memory, for the accuracy and recovery tests.
#include <depthtrack/synth.hpp>
#include <vector>

namespace depthtrack::test {

inline std::vector<SynthFrame> synthesize(const Mesh& mesh, const SynthConfig& synth) {
  const Synthesizer scene(mesh, synth);
  std::vector<SynthFrame> frames;
  for (int i = 0; i < synth.frames; ++i) frames.push_back(scene.frame(i));
  return frames;
}

}  // namespace depthtrack::test
