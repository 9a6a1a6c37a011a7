#pragma once
// The arguments of the per-particle kernels: cl/propagate.cl, cl/initialize.cl, cl/time_index.cl and
// resample.cl's fills.
#include <cstdint>

#include "compute/kernel_launch.hpp"
#include "dt_params.h"

namespace depthtrack::kernels {

struct PropagateArgs {
  Buf<float> state;  // moved in place
  unsigned count, seed_lo, seed_hi, frame;
  dt_motion motion;
  auto in_order() const { return std::tie(state, count, seed_lo, seed_hi, frame, motion); }
};

struct InitializeParticlesArgs {
  Buf<float> state;  // written
  unsigned count, seed_lo, seed_hi;
  Buf<float> modes;  // 7 floats each: translation, quaternion w x y z
  dt_initial spread;
  auto in_order() const { return std::tie(state, count, seed_lo, seed_hi, modes, spread); }
};

// Each particle's row of pixels values set to value (a group per particle).
struct FillPerParticleArgs {
  Buf<float> values;
  unsigned pixels;
  float value;
  auto in_order() const { return std::tie(values, pixels, value); }
};

struct FillArgs {
  Buf<float> values;
  unsigned count;
  float value;
  auto in_order() const { return std::tie(values, count, value); }
};

struct IdentityParentsArgs {
  Buf<unsigned> parents;
  unsigned count;
  auto in_order() const { return std::tie(parents, count); }
};

struct FillTimeIndicesArgs {
  Buf<uint16_t> indices;
  unsigned pixels, value;
  auto in_order() const { return std::tie(indices, pixels, value); }
};

struct RetireTimeIndicesArgs {
  Buf<uint16_t> indices;
  uint64_t count;
  unsigned now_index;
  auto in_order() const { return std::tie(indices, count, now_index); }
};

}  // namespace depthtrack::kernels
