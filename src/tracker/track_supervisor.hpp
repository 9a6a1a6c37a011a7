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
#include "search/visible_box.hpp"
#include "tracker/make_filter_backend.hpp"
#include "tracker/run_confidence.hpp"
#include "tracker/search_workers.hpp"
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
  // budget_ms 0: the whole coarse grid. detector_box: the hint's box bounds the object's visible pixels
  // (a detector's box, not a region to look in, as around() gives): poses whose visible pixels' box
  // disagrees with it rank below those that agree (box_agreement).
  search::SearchResult search(const DepthImage& sensor_depth, const DepthImage& working, const InitHint& hint,
                              double budget_ms, unsigned round, bool detector_box = false) const;
  // search() in two steps: the candidates of the coarse grid and its refinement, scored by the full
  // model; then their ranking (without a hint: fitted, see fit_best; in a box: see fit_confident) and
  // polish. box_regions: a box's candidates are kept region by region, as without a hint. bounds: the
  // detector's box in working pixels (search::hint_box), empty for none.
  search::SearchResult candidates(const DepthImage& sensor_depth, const DepthImage& working, const InitHint& hint,
                                  double budget_ms, unsigned round, const search::ImageBox& bounds = {},
                                  bool box_regions = false) const;
  // Returns whether the evidence chose the candidates (a box's fitted poses it supports, all together).
  // supported_apart: set where the evidence supports poses that lie apart.
  bool finish(search::SearchResult& result, const DepthImage& working, const InitHint& hint, unsigned round,
              const search::ImageBox& bounds = {}, bool* supported_apart = nullptr) const;
  // A box around where the object was at pose (its projection, widened by half its size on every side,
  // in the sensor's pixels): where a search after a gap in time looks. Anywhere when it is out of view.
  InitHint around(const Pose& pose) const;
  // The candidates to seed the filter with: the best, and the runners-up nearly as likely.
  static std::vector<Pose> seeds(const search::SearchResult& result);
  // Of those, the ones this frame's evidence supports (confidence at least loss.lost_below): after a gap
  // the likelihood alone prefers a pose explaining more pixels, and would take an unsupported one
  // elsewhere over a right pose seen by few (the YCB tuna fish can behind a 70 % occluder).
  std::vector<Pose> supported_seeds(const search::SearchResult& result, const DepthImage& working);

  // drawn, when given: the mesh's working-resolution depth at pose as the filter drew it
  // (FilterBackend::rendering_of), not drawn again.
  SilhouetteShares assess(const Pose& pose, const DepthImage& working, const std::vector<float>* drawn = nullptr);
  // The working-resolution depth of the mesh at pose (0 where it covers nothing): assess()'s rendering
  // when it drew that very pose last, else drawn now. Valid until the next assess() or silhouette().
  const std::vector<float>& silhouette(const Pose& pose);
  // Whether a search candidate ends lost: the depth supports it (confidence at least
  // loss.found_above) and it stands out from its surroundings (loss.found_outline of its outline).
  bool found(const Pose& pose, const DepthImage& working);
  struct Verdict {
    double confidence;        // to report: the frame's, or where it supports the pose, its run's (run_confidence.hpp)
    double frame_confidence;  // the frame's own: what the status follows
    TrackStatus status;
  };
  // Takes this frame's evidence, taken at time_s; the status after it is lost while the frame's own
  // confidence is below loss.lost_below.
  Verdict observe(const PoseEvidence& evidence, double time_s);
  // A gap the motion model cannot bridge: the frames before it no longer speak for the next one.
  void end_run() { run_.end_run(); }
  // Lost for loss.search_after frames in a row: the next frame searches (a shorter dip, such as a
  // passing occluder, is left to the filter).
  bool should_search() const;
  void reset();  // tracking, no lost frame counted
  TrackStatus status() const { return status_; }

 private:
  search::SearchSettings settings(const InitHint& hint, double budget_ms, unsigned round,
                                  bool box_regions = false) const;
  // Fits the best candidates to their likelihood's optimum (reference::PoseRefiner), rescored, and
  // keeps only those whose outline stands out when any does.
  void fit_best(search::SearchResult& result, const DepthImage& working) const;
  // Fits a box's best candidates, also from deeper starts, and keeps those the evidence supports when
  // they all lie together; returns whether it did. Where they lie apart, with bounds it keeps them all
  // (the likelihood ranks them), without it leaves the candidates as they were.
  bool fit_confident(search::SearchResult& result, const DepthImage& working, const search::ImageBox& bounds,
                     bool* supported_apart) const;
  // Each pose's agreement with a detector's box (bounds, working pixels): search::box_iou of the pose's
  // visible box (hidden pixels by model's band) with it; empty (no gate) when bounds is.
  search::AgreementFunction box_agreement(const search::ImageBox& bounds, const DepthImage& working,
                                          const ObservationModel& model) const;
  // Lowers by search::kDisagrees the scores of the poses that disagree with bounds (against the best of
  // them, kAgreementMargin); none when bounds is empty. One score per pose.
  void gate(std::span<const Pose> poses, std::span<double> scores, const search::ImageBox& bounds,
            const DepthImage& working) const;

  // The backend's scores of poses, their time added to times_.scoring_ms.
  std::vector<double> score(PoseScorer& scorer, std::span<const Pose> poses, const DepthImage& working,
                            const ObservationModel& model) const;
  TrackerConfig config_;
  mutable search::SearchTimes times_;  // of the search() under way
  Camera sensor_, working_;
  int decimation_;
  search::SearchObject object_;
  Mesh simplified_;                          // the coarse stages' mesh
  std::vector<Eigen::Vector3d> box_points_;  // its vertices: where a pose's visible box is sampled (on the host)
  std::unique_ptr<PoseScorer> coarse_;       // scores with the simplified mesh
  std::unique_ptr<PoseScorer> full_;         // with the tracker's mesh
  std::unique_ptr<SearchWorkers> workers_;   // the fits, silhouettes and box agreement, on the host's threads
  reference::Rasterizer rasterizer_;
  std::vector<float> scratch_;  // the mesh drawn at drawn_ (by assess or silhouette)
  std::optional<Pose> drawn_;
  TrackStatus status_ = TrackStatus::Tracking;
  int lost_frames_ = 0;  // frames in a row below loss.lost_below
  RunConfidence run_;
};

}  // namespace depthtrack
