#pragma once
// Global search: which poses to score, coarse to fine. A coarse grid (observed surface points x a
// rotation set covering SO(3)) is scored, the best distinct candidates of each region of the scene
// are kept and refined, region by region, by scoring ever finer perturbations around them. Scoring
// itself is the backend's (FilterBackend::make_pose_scorer).
#include <depthtrack/camera.hpp>
#include <depthtrack/pose.hpp>
#include <functional>
#include <span>
#include <vector>

namespace depthtrack::search {

struct Candidate {
  Pose pose;
  double score = 0;  // log-likelihood with a fresh occlusion prior, less kDisagrees where it disagrees
};

// Scores poses (camera_from_object) against the frame being searched, one value per pose.
using ScoreFunction = std::function<std::vector<double>(std::span<const Pose>)>;

// A second measure of each pose, besides its score: how well it agrees with what else is known of the
// object (in a detector's box: search::box_iou of the pose's visible box with it), larger is better.
// Poses within SearchSettings::agreement_margin of the best agreement among those compared with them
// rank above all others: their scores are lowered by kDisagrees.
using AgreementFunction = ScoreFunction;
inline constexpr double kDisagrees = 1e9;
// The agreement below which a pose disagrees: margin below the best of `agreement` (-infinity when empty).
double agreement_floor(std::span<const double> agreement, double margin);
// Lowers by kDisagrees each score whose agreement (one per score) lies below floor.
void lower_disagreeing(std::span<double> scores, std::span<const double> agreement, double floor);
// score, less kDisagrees where agreement lies below floor; one value per pose.
ScoreFunction gated(ScoreFunction score, AgreementFunction agreement, double floor);

// The candidates' poses, in their order.
std::vector<Pose> poses_of(std::span<const Candidate> candidates);

struct SearchObject {
  std::vector<Eigen::Vector3d> vertices;  // object frame
  Eigen::Vector3d centre;                 // mean of the vertices
  double radius = 0;                      // largest vertex distance from the centre
};

struct SearchSettings {
  // Spacing of the coarse grid in working pixels: neighbouring rotations move the farthest vertex
  // about this far, neighbouring translations lie this far apart.
  double coarse_pixels = 4.0;
  double finest_pixels = 0.25;  // refinement stops when its steps are this small
  int keep = 12;                // distinct candidates carried from the coarse grid, at least
  // Regions (cubes of the object's radius holding surface points) whose best candidates are
  // carried, the best-scoring first, and candidates carried per region at least: in a cluttered
  // scene the coarse model can rank another object's surface above every pose near the right one,
  // so each region keeps its own and is refined on its own.
  // Off (a box or point hint: one object's neighbourhood), all candidates compete as one region.
  bool by_region = false;
  int regions = 16, per_region = 4;
  int perturbations = 40;  // poses tried around each candidate per refinement stage
  double budget_ms = 0;    // > 0: the coarse grid is cut short to leave time for refinement
  // On (and without a budget): the coarse grid's rotations are first scored on a sparser set (at most
  // sparse_radius from any rotation), and only the grid rotations nearest the best sparse_share of those
  // (point, rotation) pairs are scored after them.
  bool two_level = false;
  double sparse_radius = 0.4;
  double sparse_share = 0.1;
  double agreement_margin = 0.3;  // with an AgreementFunction: how far below the best agreement still agrees
  uint64_t seed = 1;
  unsigned round = 0;  // varies the perturbations (and the coarse order) between searches
};

// Where a search's time went (ms, wall clock): scoring poses on the backend, each pose's agreement with a
// detector's box, and fitting the best candidates (Gauss-Newton, on the host) less the scoring and
// agreement within the fits. Filled by the caller that times its functions (TrackSupervisor).
struct SearchTimes {
  double scoring_ms = 0, box_ms = 0, fit_ms = 0;
};

struct SearchResult {
  std::vector<Candidate> candidates;  // best first, distinct (from every region carried)
  SearchTimes times;
  size_t coarse_poses = 0, poses_scored = 0;
  double rotation_radius = 0, translation_spacing = 0;  // of the coarse grid: radians, metres
};

// The coarse grid's steps, from the object's size and the surface's depth.
struct GridResolution {
  double rotation_radius = 0;      // radians: no rotation farther than this from a grid rotation
  double translation_spacing = 0;  // metres between neighbouring translations
};
GridResolution grid_resolution(const SearchObject& object, const Camera& camera,
                               std::span<const Eigen::Vector3d> surface, const SearchSettings& settings);

// surface: observed camera-frame points (search::surface_points); camera: the working camera
// scores are computed in (sets the resolution of the grid).
// agreement, when given, gates the ranking (AgreementFunction): the coarse grid's poses against the best
// of the grid (each level of a two-level grid on its own), its refinement against the same floor.
SearchResult global_search(const SearchObject& object, const Camera& camera, std::span<const Eigen::Vector3d> surface,
                           const ScoreFunction& score, const SearchSettings& settings,
                           const AgreementFunction& agreement = nullptr);

// One refinement stage's perturbation sizes (standard deviations, about the object's centre, in
// its local frame) and how many candidates survive it.
struct RefineStage {
  double radians = 0, metres = 0;
  size_t keep = 1;
};

// The seam where candidates are polished: each stage scores `perturbations` poses around every
// candidate and keeps the best distinct ones. A local optimizer of the likelihood (Gauss-Newton of
// the precision work) can take its place with the same signature.
std::vector<Candidate> refine_candidates(std::vector<Candidate> candidates, const SearchObject& object,
                                         const ScoreFunction& score, std::span<const RefineStage> stages,
                                         const SearchSettings& settings, size_t* poses_scored = nullptr);

}  // namespace depthtrack::search
