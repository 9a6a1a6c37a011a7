#pragma once
// Synthetic sequences for the tests: every frame in memory (accuracy, recovery), small occluded scenes.
#include <depthtrack/synth.hpp>
#include <vector>

namespace depthtrack::test {

inline std::vector<SynthFrame> synthesize(const Mesh& mesh, const SynthConfig& synth) {
  const Synthesizer scene(mesh, synth);
  std::vector<SynthFrame> frames;
  for (int i = 0; i < synth.frames; ++i) frames.push_back(scene.frame(i));
  return frames;
}

// A short occluded synthetic scene (30 % moving occluder) on the default sensor decimated `decimation`
// times (8: 80x60, the working resolution; 4: 160x120, decimated by the tracker).
inline SynthConfig small_scene(int frames, int decimation = 8) {
  SynthConfig synth;
  synth.camera = synth.camera.decimated(decimation);
  synth.frames = frames;
  synth.occluder_fraction = 0.3;
  return synth;
}

}  // namespace depthtrack::test
