#include "filter/track_supervisor.hpp"

#include <algorithm>
#include <cmath>

#include "search/surface_points.hpp"

namespace depthtrack {

namespace {
search::SearchObject search_object(const Mesh& mesh) {
  search::SearchObject o;
  o.centre = mesh.centre().cast<double>();
  o.radius = mesh.radius();
  o.vertices.reserve(mesh.vertices.size());
  for (const auto& v : mesh.vertices) o.vertices.push_back(v.cast<double>());
  return o;
}
}  // namespace

TrackSupervisor::TrackSupervisor(const Mesh& mesh, const Camera& sensor, const Camera& working, int decimation,
                                 const TrackerConfig& config)
    : config_(config),
      sensor_(sensor),
      working_(working),
      decimation_(decimation),
      object_(search_object(mesh)),
      rasterizer_(mesh, working, config.near_plane, config.observation.max_depth),
      scratch_(static_cast<size_t>(working.pixel_count())) {}

search::SearchResult TrackSupervisor::search(FilterBackend& backend, const DepthImage& sensor_depth,
                                             const DepthImage& working, const InitHint& hint, double budget_ms,
                                             unsigned round) const {
  search::SearchSettings settings;
  settings.budget_ms = budget_ms;
  settings.seed = config_.seed;
  settings.round = round;
  // Surface points one coarse grid step apart, found in the sensor's pixels (a box may be smaller
  // than one working pixel).
  const int stride = std::max(1, static_cast<int>(std::lround(settings.coarse_pixels * decimation_)));
  const std::vector<Eigen::Vector3d> surface =
      search::surface_points(sensor_depth, sensor_, hint, object_.radius, stride);
  const search::ScoreFunction score = [&](std::span<const Pose> poses) { return backend.score_poses(poses, working); };
  return search::global_search(object_, working_, surface, score, settings);
}

std::vector<Pose> TrackSupervisor::seeds(const search::SearchResult& result) {
  std::vector<Pose> out;
  if (result.candidates.empty()) return out;
  // Runners-up within a tenth of the best score (log-likelihoods are positive where the object
  // fits) get particles too; the next frames' weights decide among them.
  const double best = result.candidates.front().score;
  for (const auto& c : result.candidates)
    if (out.size() < 4 && c.score >= best - 0.1 * std::abs(best)) out.push_back(c.pose);
  return out;
}

SilhouetteShares TrackSupervisor::assess(const Pose& pose, const DepthImage& working) {
  return silhouette_shares(rasterizer_, config_.observation, config_.loss.pixel_sigmas, pose, working, scratch_);
}

TrackStatus TrackSupervisor::observe(double confidence) {
  bad_frames_ = confidence < config_.loss.lost_below ? bad_frames_ + 1 : 0;
  if (bad_frames_ >= config_.loss.lost_after) status_ = TrackStatus::Lost;
  // The filter can find the object again by itself (an occluder moves away).
  if (status_ == TrackStatus::Lost && confidence >= config_.loss.found_above) status_ = TrackStatus::Tracking;
  return status_;
}

void TrackSupervisor::reset() {
  status_ = TrackStatus::Tracking;
  bad_frames_ = 0;
}

}  // namespace depthtrack
