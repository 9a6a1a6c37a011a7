#include "filter/wide_summary.hpp"

#include <algorithm>

#include "dt_summary.h"
#include "filter/kernels/resample_args.hpp"
#include "filter/kernels/summary_args.hpp"

namespace depthtrack {

size_t WideSummary::groups_for(size_t particles) {
  constexpr size_t kPerWorkItem = 8, kMaxGroups = 1024;
  return std::clamp<size_t>((particles + kGroupSize * kPerWorkItem - 1) / (kGroupSize * kPerWorkItem), 1, kMaxGroups);
}

namespace {
std::vector<std::string> definitions(const std::string& occlusion_definition) {
  return {"DT_GROUP_SIZE=" + std::to_string(WideSummary::kGroupSize), occlusion_definition};
}
}  // namespace

WideSummary::WideSummary(compute::Queue& queue, compute::ProgramCache& programs,
                         const std::string& occlusion_definition, size_t particles)
    : queue_(queue),
      groups_(groups_for(particles)),
      summarize_program_(programs.program("summarize_wide.cl", definitions(occlusion_definition))),
      resample_program_(programs.program("resample.cl", definitions(occlusion_definition))),
      max_(summarize_program_->kernel("summarize_max")),
      sum_(summarize_program_->kernel("summarize_sum")),
      weights_(summarize_program_->kernel("summarize_weights")),
      karcher_(summarize_program_->kernel("summarize_karcher")),
      finish_(summarize_program_->kernel("summarize_finish")),
      totals_(resample_program_->kernel("prefix_sum_totals")),
      ranges_(resample_program_->kernel("prefix_sum_ranges")),
      partials_(queue, DT_PARTIAL_FIELDS * groups_),
      range_totals_(queue, 2 * groups_) {}

std::vector<compute::EventPtr> WideSummary::summarize(size_t particles, const compute::Buffer<float>& states,
                                                      const compute::Buffer<float>& log_weight,
                                                      const compute::Buffer<float>& log_likelihood,
                                                      compute::Buffer<float>& weights, compute::Buffer<float>& estimate,
                                                      float centre_x, float centre_y, float centre_z,
                                                      float kl_threshold, unsigned karcher_steps) {
  const size_t groups = this->groups(particles);
  const auto grid = compute::NdRange::linear(groups * kGroupSize, kGroupSize);
  const unsigned count = static_cast<unsigned>(particles);
  // Timed by its first and last launch (Event::elapsed_since_ms), as the spread refinement is.
  const compute::EventPtr first = kernels::launch(
      {queue_, *max_, grid},
      kernels::SummarizeMaxArgs{
          .log_weight = log_weight, .log_likelihood = log_likelihood, .count = count, .partials = partials_});
  kernels::launch({queue_, *sum_, grid, false},
                  kernels::SummarizeSumArgs{.log_weight = log_weight, .count = count, .partials = partials_});
  kernels::launch({queue_, *weights_, grid, false}, kernels::SummarizeWeightsArgs{.state = states,
                                                                                  .log_weight = log_weight,
                                                                                  .log_likelihood = log_likelihood,
                                                                                  .weights = weights,
                                                                                  .count = count,
                                                                                  .centre_x = centre_x,
                                                                                  .centre_y = centre_y,
                                                                                  .centre_z = centre_z,
                                                                                  .partials = partials_});
  for (unsigned step = 0; step < karcher_steps; ++step)
    kernels::launch({queue_, *karcher_, grid, false},
                    kernels::SummarizeKarcherArgs{
                        .state = states, .weights = weights, .count = count, .iteration = step, .partials = partials_});
  return {first, kernels::launch({queue_, *finish_, compute::NdRange::linear(kGroupSize, kGroupSize)},
                                 kernels::SummarizeFinishArgs{.state = states,
                                                              .estimate = estimate,
                                                              .count = count,
                                                              .groups = static_cast<unsigned>(groups),
                                                              .centre_x = centre_x,
                                                              .centre_y = centre_y,
                                                              .centre_z = centre_z,
                                                              .kl_threshold = kl_threshold,
                                                              .partials = partials_,
                                                              .karcher_steps = karcher_steps})};
}

std::vector<compute::EventPtr> WideSummary::prefix_sum(size_t particles, const compute::Buffer<float>& weights,
                                                       compute::Buffer<float>& cumulative,
                                                       const compute::Buffer<float>& estimate) {
  const size_t groups = this->groups(particles);
  const auto grid = compute::NdRange::linear(groups * kGroupSize, kGroupSize);
  const unsigned count = static_cast<unsigned>(particles);
  return {kernels::launch({queue_, *totals_, grid},
                          kernels::PrefixSumTotalsArgs{
                              .values = weights, .count = count, .totals = range_totals_, .estimate = estimate}),
          kernels::launch({queue_, *ranges_, grid}, kernels::PrefixSumRangesArgs{.values = weights,
                                                                                 .cumulative = cumulative,
                                                                                 .count = count,
                                                                                 .totals = range_totals_,
                                                                                 .estimate = estimate})};
}

}  // namespace depthtrack
