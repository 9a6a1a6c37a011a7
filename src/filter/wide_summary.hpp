#pragma once
// The frame's summary (cl/summarize_wide.cl) and the resampling's prefix sum (cl/resample.cl's
// prefix_sum_totals / prefix_sum_ranges) over many work-groups, for clouds of kWideSummaryParticles
// particles or more: summarize.cl and prefix_sum run in one work-group, which is the fastest for a few
// thousand particles (one launch each) but left one multiprocessor waiting on memory at a million
// (H200: ~10 ms a frame on CUDA, ~20 on NVIDIA OpenCL). Each pass leaves one row of partial results
// per group and the next combines them in a fixed order: the same estimate every run.
#include <algorithm>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "compute/buffer.hpp"
#include "compute/program_cache.hpp"
#include "dt_launch.h"

namespace depthtrack {

constexpr size_t kWideSummaryParticles = 16384;

class WideSummary {
 public:
  // occlusion_definition: the filter kernels' DT_OCCLUSION (model::occlusion_definition); particles:
  // the most the cloud holds (its partial rows are sized for them). Its programs are built as the filter's, with
  // kGroupSize work-items a group.
  WideSummary(compute::Queue& queue, compute::ProgramCache& programs, const std::string& occlusion_definition,
              size_t particles);

  static constexpr size_t kGroupSize = DT_FILTER_GROUP;
  // Groups for a cloud: about 8 particles a work-item, at most 1,024 groups (the partial rows each later
  // pass combines).
  static size_t groups_for(size_t particles);

  // summarize.cl's outputs (weights, estimate) from the first `particles` states and log weights (up to
  // the constructor's particles); the first and the last launch's events (the ones between are untimed:
  // device_span_ms).
  std::vector<compute::EventPtr> summarize(size_t particles, const compute::Buffer<float>& states,
                                           const compute::Buffer<float>& log_weight,
                                           const compute::Buffer<float>& log_likelihood,
                                           compute::Buffer<float>& weights, compute::Buffer<float>& estimate,
                                           float centre_x, float centre_y, float centre_z, float kl_threshold,
                                           unsigned karcher_steps);
  // prefix_sum's output (float-float cumulative weights), if the estimate says to resample.
  std::vector<compute::EventPtr> prefix_sum(size_t particles, const compute::Buffer<float>& weights,
                                            compute::Buffer<float>& cumulative, const compute::Buffer<float>& estimate);

  // The groups a cloud of count runs in (at most the constructor's particles').
  size_t groups(size_t count) const { return std::min(groups_, groups_for(count)); }

 private:
  compute::Queue& queue_;
  size_t groups_;  // the most particles'
  std::shared_ptr<compute::Program> summarize_program_, resample_program_;
  std::unique_ptr<compute::Kernel> max_, sum_, weights_, karcher_, finish_, totals_, ranges_;
  compute::Buffer<float> partials_, range_totals_;
};

}  // namespace depthtrack
