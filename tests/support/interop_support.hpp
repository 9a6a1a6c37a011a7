#pragma once
// Shared by the hand-off tests: random particles in view of the 80x60 test camera, and one pass of
// a hand-off (poses from device memory, GL's draw, the atlas back in a device buffer).
#include <random>
#include <vector>

#include "atlas/gl/atlas_renderer.hpp"
#include "compute/buffer.hpp"
#include "interop/atlas_handoff.hpp"
#include "model/particle_packing.hpp"

namespace depthtrack::test {

inline std::vector<model::ParticleState> random_particles(int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss;
  std::vector<model::ParticleState> particles(static_cast<size_t>(count));
  for (auto& p : particles) {
    p.pose = Pose(Eigen::Vector3d(0.05 * gauss(rng), 0.05 * gauss(rng), 0.7 + 0.05 * gauss(rng)),
                  Eigen::Quaterniond(gauss(rng), gauss(rng), gauss(rng), gauss(rng)));
    p.linear_velocity = Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng));  // must not disturb the pose
  }
  return particles;
}

// Renders `particles` through `handoff` (poses from device memory) and returns the atlas buffer.
inline std::vector<float> through(interop::AtlasHandoff& handoff, compute::Queue& queue,
                                  render::AtlasRenderer& renderer, const std::vector<model::ParticleState>& particles) {
  compute::Buffer<float> states(queue, particles.size() * DT_STATE_STRIDE);
  states.upload(pack_particles(particles));
  compute::Buffer<float> atlas(queue, renderer.layout().floats());
  atlas.upload(std::vector<float>(atlas.size(), -1.0f));
  handoff.send_poses(states);
  renderer.draw();
  handoff.receive_atlas(atlas);
  return atlas.download();
}

}  // namespace depthtrack::test
