// Where the error of a tracked real sequence lies: per frame, the rotation error's axis in
// the object frame (angle-axis of R_est^T R_gt), the translation error of the mesh's centre in camera
// coordinates split into along / across the viewing ray (a depth bias is along it), and the refined
// covariance's weakest axes. Starts from ground truth moved by 1 cm / 5 deg, as tests/eval/test_accuracy.cpp.
//
//   depthtrack_bench_error_axes --object 025_mug [--resolution 160x120] [--refine off] [--seed 1]
//                               [--particles 200] [--clip DIR] [--mesh FILE] [--sigma-angular RAD] ...
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <depthtrack/error.hpp>
#include <depthtrack/evaluation.hpp>
#include <numbers>
#include <string>
#include <vector>

#include "bench_args.hpp"
#include "reference/observation_model.hpp"
#include "reference/pose_refiner.hpp"
#include "reference/rasterizer.hpp"

using namespace depthtrack;

namespace {
constexpr double kDegrees = 180.0 / std::numbers::pi;

struct Options {
  std::string object = "025_mug";
  std::string clip = std::string(DEPTHTRACK_DATA_DIR) + "/sequences/ycbv-0000";
  std::string mesh;  // default: meshes/ycb/<object>.obj
  std::pair<int, int> size = {160, 120};
  bool refine = true;
  int seed = 1;
  int particles = 200;
  std::pair<int, int> fine = {0, 0};  // refit each frame's estimate at this resolution afterwards (0: not)
  bool scan = false;                  // at the last frame: the likelihood along the rotation error's axis
  TrackerConfig config;               // the model's parameters, defaults unless an option below sets one
};

void usage() {
  std::puts(
      "usage: depthtrack_bench_error_axes [--object NAME] [--clip DIR] [--mesh FILE] [--resolution WxH]\n"
      "                                   [--refine on|off] [--seed N] [--particles N] [--sigma-angular RAD]\n"
      "                                   [--sigma-linear M] [--tail-weight W] [--min-incidence COS]\n"
      "                                   [--refine-iterations N] [--scan] [--fine-refit WxH]   (model parameters per "
      "TrackerConfig)");
}

Options parse(int argc, char** argv) {
  Options o;
  bench::ArgReader args(argc, argv);
  for (std::string option = args.next(); !option.empty(); option = args.next()) {
    if (option == "--help") {
      usage();
      std::exit(0);
    } else if (option == "--object") {
      o.object = args.value();
    } else if (option == "--clip") {
      o.clip = args.value();
    } else if (option == "--mesh") {
      o.mesh = args.value();
    } else if (option == "--resolution") {
      o.size = bench::parse_size(args.value(), option);
    } else if (option == "--refine") {
      const std::string v = args.value();
      if (v != "on" && v != "off") throw bench::UsageError{"--refine takes on or off, not '" + v + "'"};
      o.refine = v == "on";
    } else if (option == "--seed") {
      o.seed = bench::parse_positive(args.value(), option);
    } else if (option == "--particles") {
      o.particles = bench::parse_positive(args.value(), option);
    } else if (option == "--fine-refit") {
      o.fine = bench::parse_size(args.value(), option);
    } else if (option == "--scan") {
      o.scan = true;
    } else if (option == "--sigma-angular") {
      o.config.motion.sigma_angular = bench::parse_nonnegative_double(args.value(), option);
    } else if (option == "--sigma-linear") {
      o.config.motion.sigma_linear = bench::parse_nonnegative_double(args.value(), option);
    } else if (option == "--tail-weight") {
      o.config.observation.tail_weight = bench::parse_nonnegative_double(args.value(), option);
    } else if (option == "--min-incidence") {
      o.config.refine.min_incidence = bench::parse_nonnegative_double(args.value(), option);
    } else if (option == "--refine-iterations") {
      o.config.refine.iterations = bench::parse_positive(args.value(), option);
    } else {
      throw bench::UsageError{"unknown option '" + option + "'"};
    }
  }
  if (o.mesh.empty()) o.mesh = std::string(DEPTHTRACK_DATA_DIR) + "/meshes/ycb/" + o.object + ".obj";
  return o;
}

// Largest standard deviation of a 3x3 covariance and its axis.
double weakest_axis(const Eigen::Matrix3d& c, Eigen::Vector3d& axis) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(c);
  axis = solver.eigenvectors().col(2);
  return std::sqrt(std::max(0.0, solver.eigenvalues()(2)));
}

// Per frame, the log-likelihood (uniform occlusion prior) of the estimate turned by theta about the
// rotation error's axis through its centre, for theta from -0.5x to 1.5x the error (1: the truth's
// rotation at the estimate's centre), and of the truth itself; with the pixels seen far behind
// (background where the pose puts the object, the silhouette's evidence) at the estimate and at 1x, and
// the median signed depth residual near the surface at the estimate and at the truth (a depth bias).
void print_scan(const Mesh& mesh, const Sequence& sequence, const TrackerConfig& config,
                const std::vector<TrackedFrame>& frames) {
  const int factor = sequence.camera.decimation_factor_for(config.width, config.height);
  const Camera camera = sequence.camera.decimated(factor);
  const reference::PoseRefiner refiner(mesh, camera, config);
  reference::Rasterizer rasterizer(mesh, camera, config.near_plane, config.observation.max_depth);
  const std::vector<double> occlusion(static_cast<size_t>(camera.pixel_count()), config.occlusion.initial);
  std::vector<float> rendered(static_cast<size_t>(camera.pixel_count()));
  const Eigen::Vector3d centre = mesh.centre().cast<double>();
  std::printf(
      "\nscan about the rotation error's axis (share of the error; 1 = the truth's rotation at the estimate's "
      "centre)\nframe  error deg  log L at share -0.5 -0.25 0 0.25 0.5 0.75 1 1.25 1.5   best share  log L of "
      "truth  far behind at 0 / 1   median y - y_hat mm, estimate / truth\n");
  for (size_t i = 0; i < frames.size(); ++i) {
    const DepthImage depth = sequence.load_depth(i).decimated(factor);
    const Pose& est = frames[i].estimate.pose;
    const Pose& truth = *frames[i].ground_truth;
    const Eigen::Vector3d error_rotation = rotation_log(est.rotation.conjugate() * truth.rotation);
    // Pixels seen far behind the pose's surface, and the median signed residual y - y_hat of those
    // seen near it (> 0: the measured surface lies behind the rendered one).
    auto silhouette_and_bias = [&](const Pose& pose, double& median_residual) {
      rasterizer.render(pose, rendered);
      int behind = 0;
      std::vector<double> near;
      for (size_t k = 0; k < rendered.size(); ++k) {
        const double y = depth.data()[k], y_hat = rendered[k];
        if (y_hat <= 0 || !DepthImage::is_valid(static_cast<float>(y))) continue;
        const double band = 3 * reference::depth_sigma(config.observation, y);
        behind += y > y_hat + band;
        if (std::abs(y - y_hat) <= band) near.push_back(y - y_hat);
      }
      std::nth_element(near.begin(), near.begin() + static_cast<std::ptrdiff_t>(near.size() / 2), near.end());
      median_residual = near.empty() ? NAN : near[near.size() / 2];
      return behind;
    };
    std::printf("%5zu  %8.2f  ", i, kDegrees * error_rotation.norm());
    double best = -INFINITY, best_share = 0;
    int behind_0 = 0, behind_1 = 0;
    double bias_estimate = NAN, bias_rotated = NAN, bias_truth = NAN;
    for (int step = -2; step <= 6; ++step) {
      const double share = step / 4.0;
      const Eigen::Quaterniond rotation = est.rotation * rotation_exp(share * error_rotation);
      const Pose pose(est.apply(centre) - rotation * centre, rotation);
      const double objective = refiner.normal_equations(pose, depth, occlusion).objective;
      std::printf(" %7.1f", objective);
      if (objective > best) best = objective, best_share = share;
      if (step == 0) behind_0 = silhouette_and_bias(pose, bias_estimate);
      if (step == 4) behind_1 = silhouette_and_bias(pose, bias_rotated);
    }
    silhouette_and_bias(truth, bias_truth);
    std::printf("   %5.2f  %9.1f  %4d / %d   %+5.2f %+5.2f\n", best_share,
                refiner.normal_equations(truth, depth, occlusion).objective, behind_0, behind_1, 1000 * bias_estimate,
                1000 * bias_truth);
  }
}

// Each frame's estimate refitted afterwards by the reference fit at a finer resolution (uniform
// occlusion prior; the filter itself is not changed): does the fit's pixel count alone hold the
// weakly observed axes? Prints the same error columns as print_frames, without the covariance.
void print_fine_refit(const Mesh& mesh, const Sequence& sequence, const TrackerConfig& config,
                      const std::vector<TrackedFrame>& frames, std::pair<int, int> size) {
  const int factor = sequence.camera.decimation_factor_for(size.first, size.second);
  const Camera camera = sequence.camera.decimated(factor);
  const reference::PoseRefiner refiner(mesh, camera, config);
  const std::vector<double> occlusion(static_cast<size_t>(camera.pixel_count()), config.occlusion.initial);
  const Eigen::Vector3d centre = mesh.centre().cast<double>();
  const AddsMetric adds(mesh);
  std::printf("\nrefitted at %dx%d: frame  r deg  t mm  along-ray  ADD-S\n", size.first, size.second);
  double sum_t = 0, sum_r = 0;
  for (size_t i = 0; i < frames.size(); ++i) {
    const DepthImage depth = sequence.load_depth(i).decimated(factor);
    const Pose pose = refiner.refine(frames[i].estimate.pose, depth, occlusion).pose;
    const Pose& truth = *frames[i].ground_truth;
    const Eigen::Vector3d dt = pose.apply(centre) - truth.apply(centre);
    const double r = rotation_error(pose, truth);
    sum_t += dt.norm();
    sum_r += r;
    std::printf("%5zu %6.2f  %5.2f  %+6.2f  %6.2f\n", i, kDegrees * r, 1000 * dt.norm(),
                1000 * dt.dot(truth.apply(centre).normalized()), 1000 * adds(pose, truth));
  }
  const double n = static_cast<double>(frames.size());
  std::printf("refitted mean  %6.2f deg, %.2f mm\n", kDegrees * sum_r / n, 1000 * sum_t / n);
}

void print_frames(const Options& o) {
  const Mesh mesh = Mesh::load(o.mesh);
  const Sequence sequence = load_sequence(o.clip, o.object);
  for (const SequenceFrame& frame : sequence.frames)
    if (!frame.ground_truth) throw InputError("frame " + frame.name + " of " + o.clip + " has no ground truth");
  if (sequence.frames.empty()) throw InputError(o.clip + " has no frames");
  TrackerConfig config = o.config;
  config.width = o.size.first;
  config.height = o.size.second;
  config.seed = static_cast<uint64_t>(o.seed);
  config.particles = o.particles;
  config.refine.enabled = o.refine;
  const Eigen::Vector3d centre = mesh.centre().cast<double>();
  const Pose start = perturb_pose(*sequence.frames.front().ground_truth, centre, 0.01, 5.0, 1);
  const auto frames = track_sequence(sequence, mesh, config, start, InitialSpread{0.01, 5.0 / kDegrees});

  std::printf("%s, %dx%d, refine %s, seed %d, %d particles, sigma %.4f m / %.4f rad, tail %.3f, incidence %.2f\n",
              o.object.c_str(), o.size.first, o.size.second, o.refine ? "on" : "off", o.seed, o.particles,
              config.motion.sigma_linear, config.motion.sigma_angular, config.observation.tail_weight,
              config.refine.min_incidence);
  std::printf(
      "frame  r deg  r axis (object frame)   t mm  along-ray  across   ADD-S   "
      "cov: sd_t mm |cos ray|  sd_r deg  axis (object frame)  |cos| to r axis\n");
  double sum_t = 0, sum_r = 0, sum_along = 0, sum_across = 0;
  for (size_t i = 0; i < frames.size(); ++i) {
    const TrackedFrame& f = frames[i];
    const Pose& est = f.estimate.pose;
    const Pose& gt = *f.ground_truth;
    const Eigen::Vector3d error_rotation = rotation_log(est.rotation.conjugate() * gt.rotation);
    const double angle = error_rotation.norm();
    const Eigen::Vector3d axis = angle > 0 ? Eigen::Vector3d(error_rotation / angle) : Eigen::Vector3d::Zero();
    const Eigen::Vector3d gt_centre = gt.apply(centre);
    const Eigen::Vector3d dt = est.apply(centre) - gt_centre;
    const Eigen::Vector3d ray = gt_centre.normalized();
    const double along = dt.dot(ray), across = (dt - along * ray).norm();
    sum_t += dt.norm();
    sum_r += angle;
    sum_along += along;
    sum_across += across;
    std::printf("%5zu %6.2f  (%+.2f %+.2f %+.2f)    %5.2f  %+6.2f  %6.2f  %6.2f", i, kDegrees * angle, axis(0), axis(1),
                axis(2), 1000 * dt.norm(), 1000 * along, 1000 * across, 1000 * f.adds);
    const Eigen::Matrix<double, 6, 6>& cov = f.estimate.covariance;
    if (cov.allFinite()) {
      Eigen::Vector3d t_axis, r_axis;
      const double sd_t = weakest_axis(cov.topLeftCorner<3, 3>(), t_axis);
      const Eigen::Matrix3d object_from_camera = est.rotation.conjugate().toRotationMatrix();
      const double sd_r =
          weakest_axis(object_from_camera * cov.bottomRightCorner<3, 3>() * object_from_camera.transpose(), r_axis);
      std::printf("   %7.3f  %5.2f   %7.3f  (%+.2f %+.2f %+.2f)  %.2f", 1000 * sd_t, std::abs(t_axis.dot(ray)),
                  kDegrees * sd_r, r_axis(0), r_axis(1), r_axis(2), std::abs(r_axis.dot(axis)));
    }
    std::printf("\n");
  }
  const double n = static_cast<double>(frames.size());
  std::printf("mean  %6.2f deg, %.2f mm (along ray %+.2f, across %.2f), last ADD-S %.2f mm\n", kDegrees * sum_r / n,
              1000 * sum_t / n, 1000 * sum_along / n, 1000 * sum_across / n, 1000 * frames.back().adds);
  if (o.scan) print_scan(mesh, sequence, config, frames);
  if (o.fine.first > 0) print_fine_refit(mesh, sequence, config, frames, o.fine);
}
}  // namespace

int main(int argc, char** argv) {
  try {
    print_frames(parse(argc, argv));
  } catch (const bench::UsageError& e) {
    std::fprintf(stderr, "depthtrack_bench_error_axes: %s\n", e.message.c_str());
    usage();
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "depthtrack_bench_error_axes: %s\n", e.what());
    return 1;
  }
}
