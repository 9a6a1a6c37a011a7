#pragma once
// The arguments of the summary's kernels: cl/summarize.cl's one group and cl/summarize_wide.cl's passes.
#include "compute/kernel_launch.hpp"

namespace depthtrack::kernels {

struct SummarizeArgs {
  Buf<float> state, log_weight, log_likelihood;
  Buf<float> weights, estimate;  // written
  unsigned count;
  float centre_x, centre_y, centre_z, kl_threshold;
  unsigned karcher_steps;
  auto in_order() const {
    return std::tie(state, log_weight, log_likelihood, weights, estimate, count, centre_x, centre_y, centre_z,
                    kl_threshold, karcher_steps);
  }
};

struct SummarizeMaxArgs {
  Buf<float> log_weight, log_likelihood;
  unsigned count;
  Buf<float> partials;
  auto in_order() const { return std::tie(log_weight, log_likelihood, count, partials); }
};

struct SummarizeSumArgs {
  Buf<float> log_weight;
  unsigned count;
  Buf<float> partials;
  auto in_order() const { return std::tie(log_weight, count, partials); }
};

struct SummarizeWeightsArgs {
  Buf<float> state, log_weight, log_likelihood;
  Buf<float> weights;  // written
  unsigned count;
  float centre_x, centre_y, centre_z;
  Buf<float> partials;
  auto in_order() const {
    return std::tie(state, log_weight, log_likelihood, weights, count, centre_x, centre_y, centre_z, partials);
  }
};

struct SummarizeKarcherArgs {
  Buf<float> state, weights;
  unsigned count, iteration;
  Buf<float> partials;
  auto in_order() const { return std::tie(state, weights, count, iteration, partials); }
};

struct SummarizeFinishArgs {
  Buf<float> state;
  Buf<float> estimate;  // written
  unsigned count, groups;
  float centre_x, centre_y, centre_z, kl_threshold;
  Buf<float> partials;
  unsigned karcher_steps;
  auto in_order() const {
    return std::tie(state, estimate, count, groups, centre_x, centre_y, centre_z, kl_threshold, partials,
                    karcher_steps);
  }
};

}  // namespace depthtrack::kernels
