#pragma once
// The Tracker's backend-independent layer above the filter: global search for a frame (through
// pose scorers the backend makes on its device), each estimate's confidence from its rendered
// silhouette, and the lost/tracking status with hysteresis over frames.
#include <depthtrack/camera.hpp>
#include <depthtrack/init_hint.hpp>
#include <depthtrack/tracker.hpp>
#include <optional>
#include <vector>

#include "model/filter_backend.hpp"
#include "reference/pose_refiner.hpp"
#include "reference/rasterizer.hpp"
#include "search/global_search.hpp"
#include "tracker/make_filter_backend.hpp"
#include "tracker/silhouette_shares.hpp"

namespace depthtrack {

class TrackSupervisor {
 public:
  // backend makes the search's scorers (their programs are built here, with the tracker's).
  TrackSupervisor(FilterBackend& backend, const Mesh& mesh, const Camera& sensor, const Camera& working, int decimation,
                  const TrackerConfig& config);

  // Searches one frame: the coarse grid and its refinement scored with a simplified copy of the
  // mesh (search::simplify_mesh), the last stage and the final ranking with the full mesh.
  // sensor_depth: as received (the hint's box is in its pixels); working: the frame scored.
  // budget_ms 0: the whole coarse grid.
  search::SearchResult search(const DepthImage& sensor_depth, const DepthImage& working, const InitHint& hint,
                              double budget_ms, unsigned round) const;
  // search() in two steps: the candidates of the coarse grid and its refinement, scored by the full
  // model; then their ranking (without a hint: fitted, see fit_best) and polish.
  search::SearchResult candidates(const DepthImage& sensor_depth, const DepthImage& working, const InitHint& hint,
                                  double budget_ms, unsigned round) const;
  void finish(search::SearchResult& result, const DepthImage& working, const InitHint& hint, unsigned round) const;
  // The candidates to seed the filter with: the best, and the runners-up nearly as likely.
  static std::vector<Pose> seeds(const search::SearchResult& result);

  SilhouetteShares assess(const Pose& pose, const DepthImage& working);
  // The working-resolution depth of the mesh at pose (0 where it covers nothing): assess()'s rendering
  // when it drew that very pose last, else drawn now. Valid until the next assess() or silhouette().
  const std::vector<float>& silhouette(const Pose& pose);
  // Whether a search candidate ends lost: the depth explains its silhouette (confidence at least
  // loss.found_above) and it stands out from its surroundings (loss.found_outline of its outline).
  bool found(const Pose& pose, const DepthImage& working);
  // Takes this frame's confidence; returns the status after it.
  TrackStatus observe(double confidence);
  void reset();  // tracking, no bad frame counted
  TrackStatus status() const { return status_; }

 private:
  search::SearchSettings settings(const InitHint& hint, double budget_ms, unsigned round) const;
  // Fits the best candidates to their likelihood's optimum (reference::PoseRefiner), rescored, and
  // keeps only those whose outline stands out when any does.
  void fit_best(search::SearchResult& result, const DepthImage& working) const;

  TrackerConfig config_;
  Camera sensor_, working_;
  int decimation_;
  search::SearchObject object_;
  std::unique_ptr<PoseScorer> coarse_;  // scores with the simplified mesh
  std::unique_ptr<PoseScorer> full_;    // with the tracker's mesh
  reference::PoseRefiner refiner_;      // fits the best candidates without a hint (on the host)
  reference::Rasterizer rasterizer_;
  std::vector<float> scratch_;  // the mesh drawn at drawn_ (by assess or silhouette)
  std::optional<Pose> drawn_;
  TrackStatus status_ = TrackStatus::Tracking;
  int bad_frames_ = 0;
};

}  // namespace depthtrack
