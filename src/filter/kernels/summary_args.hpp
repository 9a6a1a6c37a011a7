#pragma once
// The arguments of the summary's kernels: cl/summarize.cl's one-launch summaries and cl/summarize_wide.cl's
// passes.
#include <variant>

#include "compute/kernel_launch.hpp"

namespace depthtrack::kernels {

// What the frame's summary reads and writes (FrameSteps::summarize gives it to the plan's summary kernel).
struct SummaryInputs {
  Buf<float> state, log_weight, log_likelihood;
  Buf<float> weights, estimate;  // written
  unsigned count;
  float centre_x, centre_y, centre_z, kl_threshold;
  unsigned karcher_steps;
};

// cl/summarize.cl's summarize: the summary in one work-group.
struct SummarizeArgs {
  static constexpr const char* kernel = "summarize";
  Buf<float> state, log_weight, log_likelihood;
  Buf<float> weights, estimate;  // written
  unsigned count;
  float centre_x, centre_y, centre_z, kl_threshold;
  unsigned karcher_steps;
  static SummarizeArgs from(const SummaryInputs& in) {
    return {in.state,    in.log_weight, in.log_likelihood, in.weights,      in.estimate,     in.count,
            in.centre_x, in.centre_y,   in.centre_z,       in.kl_threshold, in.karcher_steps};
  }
  auto in_order() const {
    return std::tie(state, log_weight, log_likelihood, weights, estimate, count, centre_x, centre_y, centre_z,
                    kl_threshold, karcher_steps);
  }
};

// A one-launch summary kernel of cl/summarize.cl, by its arguments' type: FramePlan::summary_kernel names
// one, and FrameSteps builds Args::kernel and launches it with Args::from the frame's SummaryInputs, in
// one group of FramePlan::summary_group work-items. A new variant is a struct like SummarizeArgs, listed here.
template <class Args>
struct SummaryKernelOf {
  using Arguments = Args;
};
using SummaryKernel = std::variant<SummaryKernelOf<SummarizeArgs>>;

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
