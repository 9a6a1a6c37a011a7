#pragma once
// Particle weights in log space: normalization, degeneracy measures, systematic resampling.
#include <span>
#include <vector>

namespace depthtrack::reference {

struct WeightSummary {
  std::vector<double> normalized;  // sum to 1
  double effective_sample_size;    // 1 / sum w^2
  double kl_from_uniform;          // log N - H(w): dbot's degeneracy measure
};

// Normalizes log weights by subtracting the maximum (log-sum-exp), so no weight underflows to all-zero.
WeightSummary summarize_log_weights(std::span<const double> log_weights);

// Low-variance resampling: child j takes the first parent whose cumulative weight exceeds
// (u + j) / N, u in [0, 1). Returns each child's parent index.
std::vector<int> systematic_resample(std::span<const double> normalized, double u);
// The same with `children` children ((u + j) / children), from N parents: what changes the particle count.
std::vector<int> systematic_resample(std::span<const double> normalized, double u, size_t children);

}  // namespace depthtrack::reference
