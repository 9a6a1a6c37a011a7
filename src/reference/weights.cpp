#include "reference/weights.hpp"

#include <algorithm>
#include <cmath>

namespace depthtrack::reference {

WeightSummary summarize_log_weights(std::span<const double> log_weights) {
  WeightSummary s;
  const double n = static_cast<double>(log_weights.size());
  const double max = *std::max_element(log_weights.begin(), log_weights.end());
  s.normalized.resize(log_weights.size());
  double sum = 0;
  for (size_t i = 0; i < log_weights.size(); ++i) sum += s.normalized[i] = std::exp(log_weights[i] - max);
  double sum_sq = 0, entropy = 0;
  for (double& w : s.normalized) {
    w /= sum;
    sum_sq += w * w;
    if (w > 0) entropy -= w * std::log(w);
  }
  s.effective_sample_size = 1.0 / sum_sq;
  s.kl_from_uniform = std::log(n) - entropy;
  return s;
}

std::vector<int> systematic_resample(std::span<const double> normalized, double u) {
  return systematic_resample(normalized, u, normalized.size());
}

std::vector<int> systematic_resample(std::span<const double> normalized, double u, size_t children) {
  const size_t n = normalized.size();
  std::vector<int> parents(children);
  double cumulative = normalized[0];
  size_t parent = 0;
  for (size_t child = 0; child < children; ++child) {
    const double position = (u + static_cast<double>(child)) / static_cast<double>(children);
    while (cumulative <= position && parent + 1 < n) cumulative += normalized[++parent];
    parents[child] = static_cast<int>(parent);
  }
  return parents;
}

}  // namespace depthtrack::reference
