// Tracks three synthetic frames through the installed library; exit code 0 when it tracks.
#include <cstdio>
#include <depthtrack/synth.hpp>
#include <depthtrack/tracker.hpp>

int main() {
  const depthtrack::Mesh mesh = depthtrack::builtin_demo_mesh();
  depthtrack::SynthConfig synth;
  synth.frames = 3;
  const depthtrack::Synthesizer scene(mesh, synth);
  depthtrack::TrackerConfig config;
  config.particles = 50;
  depthtrack::Tracker tracker(mesh, synth.camera, config);
  tracker.initialize(scene.ground_truth(0.0));
  double error = 0;
  for (int i = 0; i < synth.frames; ++i) {
    const auto frame = scene.frame(i);
    error = depthtrack::translation_error(tracker.update(frame.depth, frame.timestamp).pose, frame.ground_truth);
  }
  std::printf("consumer: last translation error %.2f mm\n", error * 1000);
  return error < 0.02 ? 0 : 1;
}
