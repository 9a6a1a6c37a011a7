#pragma once
// Particle states <-> the float layout of device memory (cl/dt_state.h).
#include <vector>

#include "core/pose_state.hpp"
#include "dt_state.h"
#include "model/particle.hpp"

namespace depthtrack {

inline std::vector<float> pack_particles(const std::vector<model::ParticleState>& states) {
  std::vector<float> out(states.size() * DT_STATE_STRIDE, 0.0f);
  for (size_t i = 0; i < states.size(); ++i) {
    float* p = out.data() + i * DT_STATE_STRIDE;
    const model::ParticleState& s = states[i];
    write_pose(s.pose, p);
    for (int k = 0; k < 3; ++k) {
      p[DT_VX + k] = static_cast<float>(s.linear_velocity[k]);
      p[DT_WX + k] = static_cast<float>(s.angular_velocity[k]);
    }
  }
  return out;
}

inline std::vector<model::ParticleState> unpack_particles(const std::vector<float>& packed) {
  std::vector<model::ParticleState> out(packed.size() / DT_STATE_STRIDE);
  for (size_t i = 0; i < out.size(); ++i) {
    const float* p = packed.data() + i * DT_STATE_STRIDE;
    out[i].pose = read_pose(p);
    out[i].linear_velocity = Eigen::Vector3d(p[DT_VX], p[DT_VX + 1], p[DT_VX + 2]);
    out[i].angular_velocity = Eigen::Vector3d(p[DT_WX], p[DT_WX + 1], p[DT_WX + 2]);
  }
  return out;
}

}  // namespace depthtrack
