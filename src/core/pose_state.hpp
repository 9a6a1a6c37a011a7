#pragma once
// A pose as the floats of a particle state (cl/dt_state.h): translation at DT_TX, quaternion
// w, x, y, z at DT_QW. Shared by the device filter's packing and the GL renderer's pose buffer.
#include <depthtrack/pose.hpp>

#include "dt_state.h"

namespace depthtrack {

inline void write_pose(const Pose& pose, float* state) {
  for (int k = 0; k < 3; ++k) state[DT_TX + k] = static_cast<float>(pose.translation[k]);
  state[DT_QW] = static_cast<float>(pose.rotation.w());
  state[DT_QW + 1] = static_cast<float>(pose.rotation.x());
  state[DT_QW + 2] = static_cast<float>(pose.rotation.y());
  state[DT_QW + 3] = static_cast<float>(pose.rotation.z());
}

inline Pose read_pose(const float* state) {
  return Pose({state[DT_TX], state[DT_TX + 1], state[DT_TX + 2]},
              Eigen::Quaterniond(state[DT_QW], state[DT_QW + 1], state[DT_QW + 2], state[DT_QW + 3]));
}

}  // namespace depthtrack
