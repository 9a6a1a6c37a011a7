#include "eval/case_scores.hpp"

#include <algorithm>
#include <cmath>

#include "core/convex_hull.hpp"

namespace depthtrack {

double adds_auc(const std::vector<double>& adds, double max) {
  double sum = 0;
  size_t n = 0;
  for (double d : adds) {
    if (std::isnan(d)) continue;
    sum += std::max(0.0, 1.0 - d / max);
    ++n;
  }
  return n == 0 ? NAN : sum / static_cast<double>(n);
}

MeshDiameter mesh_diameter(const Mesh& mesh) {
  const auto hull = convex_hull_vertices(mesh.vertices);
  if (!hull) {
    Eigen::Vector3f low = Eigen::Vector3f::Constant(INFINITY), high = -low;
    for (const auto& v : mesh.vertices) {
      low = low.cwiseMin(v);
      high = high.cwiseMax(v);
    }
    return {mesh.vertices.empty() ? 0.0 : (high - low).cast<double>().norm(), false};
  }
  double largest = 0;
  for (size_t i = 0; i < hull->size(); ++i)
    for (size_t j = i + 1; j < hull->size(); ++j)
      largest = std::max(
          largest, (mesh.vertices[static_cast<size_t>((*hull)[i])] - mesh.vertices[static_cast<size_t>((*hull)[j])])
                       .cast<double>()
                       .squaredNorm());
  return {std::sqrt(largest), true};
}

double adds_tolerance(double diameter) {
  return std::min(0.010, 0.1 * diameter);
}

bool confident_wrong(const TrackedFrame& f) {
  return f.adds > kConfidentWrongAdds && f.estimate.status == TrackStatus::Tracking &&
         f.estimate.confidence >= kConfidentAbove;
}

CaseScores score_case(const std::vector<TrackedFrame>& frames, double tolerance, std::optional<size_t> recovery_from) {
  CaseScores s;
  s.frames = frames.size();
  std::vector<double> adds;
  double sum = 0;
  for (const TrackedFrame& f : frames) {
    const TrackStatus status = f.estimate.status;
    s.tracking += status == TrackStatus::Tracking;
    s.lost += status == TrackStatus::Lost;
    s.no_data += status == TrackStatus::NoData;
    adds.push_back(f.adds);
    if (std::isnan(f.adds)) continue;
    ++s.scored;
    sum += f.adds;
    s.confident_wrong += confident_wrong(f);
    s.false_lost += status == TrackStatus::Lost && f.adds <= tolerance;
  }
  if (s.scored > 0) s.mean_adds = sum / static_cast<double>(s.scored);
  s.auc = adds_auc(adds);
  if (!frames.empty()) s.last_adds = frames.back().adds;
  if (recovery_from && *recovery_from < frames.size())
    s.recovered = std::all_of(
        frames.begin() + static_cast<std::ptrdiff_t>(*recovery_from), frames.end(), [](const TrackedFrame& f) {
          return std::isnan(f.adds) || f.estimate.status == TrackStatus::Lost || f.adds <= kEndsWithin;
        });
  return s;
}

Reliability reliability(const std::vector<ConfidenceOutcome>& outcomes) {
  Reliability r;
  std::array<double, 10> confidence_sum{}, within_sum{};
  for (const ConfidenceOutcome& o : outcomes) {
    if (!std::isfinite(o.confidence)) continue;
    const size_t bin = std::min<size_t>(9, static_cast<size_t>(std::max(0.0, std::floor(o.confidence * 10))));
    ++r.bins[bin].frames;
    confidence_sum[bin] += o.confidence;
    within_sum[bin] += o.within ? 1.0 : 0.0;
    ++r.frames;
  }
  if (r.frames == 0) return r;
  r.ece = 0;
  for (size_t b = 0; b < r.bins.size(); ++b) {
    ReliabilityBin& bin = r.bins[b];
    if (bin.frames == 0) continue;
    const double n = static_cast<double>(bin.frames);
    bin.mean_confidence = confidence_sum[b] / n;
    bin.share_within = within_sum[b] / n;
    r.ece += n / static_cast<double>(r.frames) * std::abs(bin.share_within - bin.mean_confidence);
  }
  return r;
}

}  // namespace depthtrack
