#pragma once
// The arguments of cl/resample.cl's prefix sums and resampling gathers.
#include "compute/kernel_launch.hpp"

namespace depthtrack::kernels {

struct PrefixSumArgs {
  Buf<float> values;
  Buf<float> cumulative;  // written: float-float pairs
  unsigned count;
  Buf<float> estimate;  // its resampling flag
  auto in_order() const { return std::tie(values, cumulative, count, estimate); }
};

struct PrefixSumTotalsArgs {
  Buf<float> values;
  unsigned count;
  Buf<float> totals;  // written: a float-float pair per group
  Buf<float> estimate;
  auto in_order() const { return std::tie(values, count, totals, estimate); }
};

struct PrefixSumRangesArgs {
  Buf<float> values;
  Buf<float> cumulative;  // written
  unsigned count;
  Buf<float> totals, estimate;
  auto in_order() const { return std::tie(values, cumulative, count, totals, estimate); }
};

// The gather of the children's states from `from` into `to`, moved by the correction where shift:
// resample_particles (after a prefix sum) and resample_scanning (each group scanning the weights itself)
// take the same arguments but the first.
struct ResampleArgs {
  Buf<float> weights;     // resample_scanning: the weights; resample_particles: their prefix sum
  Buf<unsigned> parents;  // written
  unsigned count;
  float u;
  Buf<float> estimate, from;
  Buf<float> to, log_weight;  // written
  Buf<float> correction;
  float centre_x, centre_y, centre_z;
  unsigned shift;
  auto in_order() const {
    return std::tie(weights, parents, count, u, estimate, from, to, log_weight, correction, centre_x, centre_y,
                    centre_z, shift);
  }
};

// Child j of count takes particle choice[j]'s kinematic state from `from` into `to`.
struct GatherStatesArgs {
  Buf<unsigned> choice;
  unsigned count;
  Buf<float> from;
  Buf<float> to;  // written
  auto in_order() const { return std::tie(choice, count, from, to); }
};

}  // namespace depthtrack::kernels
