// The peer users pick instead of depthtrack: PCL's KLD-adaptive particle filter tracker
// (pcl::tracking), run on exactly the frames depthtrack reads (depthtrack's library loads the
// sequence, mesh, intrinsics and decimation) from exactly its start (perturb_pose with the same
// seed as `depthtrack track --init-perturb`). Writes the CSV `depthtrack track` writes.
//
// Per frame: the decimated depth image is back-projected to a point cloud, cropped to a sphere
// around the previous estimate (the ROI), and the tracker weighs its particles by how many of the
// model's points find an observed point nearby. The model is the mesh surface sampled by area;
// because pcl::tracking 1.13 discards the visibility indices its normal test computes (the cloud
// coherences ignore them), the points seen from the camera at the previous estimate are selected
// here with depthtrack's rasterizer and handed to the tracker as its reference cloud.
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>
#include <pcl/search/octree.h>
#include <pcl/tracking/approx_nearest_pair_point_cloud_coherence.h>
#include <pcl/tracking/distance_coherence.h>
#include <pcl/tracking/kld_adaptive_particle_filter_omp.h>
#include <pcl/tracking/nearest_pair_point_cloud_coherence.h>
#include <pcl/tracking/normal_coherence.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <depthtrack/error.hpp>
#include <depthtrack/evaluation.hpp>
#include <depthtrack/tracker_config.hpp>
#include <iostream>
#include <nanoflann.hpp>
#include <numbers>
#include <optional>
#include <random>

#include "peer_run.hpp"
#include "reference/rasterizer.hpp"

using namespace depthtrack;
using Point = pcl::PointNormal;
using Cloud = pcl::PointCloud<Point>;
using State = pcl::tracking::ParticleXYZRPY;
using PclTracker = pcl::tracking::KLDAdaptiveParticleFilterOMPTracker<Point, State>;

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

struct Options {
  peers::PeerOptions common;
  std::string init_spread = "0.01 5";
  std::string step_noise = "0.002 1.5";  // metres, degrees: standard deviation per axis per frame
  int particles = 200, max_particles = 1000, samples = 3000, threads = 1;
  double bin_size = 0.01;  // metres and radians: KLD histogram cell
  double epsilon = 0.2, delta = 0.99;
  double max_distance = 0.01;     // metres: a model point farther than this from every observed point scores 0
  double distance_sigma = 0.004;  // metres: DistanceCoherence weight = 1 / sigma^2
  double normal_weight = 0.0;     // NormalCoherence weight (0 = off)
  double roi_margin = 0.03;       // metres beyond the mesh's radius around the previous estimate
  double visible_tolerance = 0.005;
  double alpha = 30.0;  // PCL's default 15; 30 measured a little better, 5, 20, 60, 120 worse
  double motion_ratio = 0.25;
  // nanoflann, kdtree, octree (exact nearest pairs) or approx (PCL's approximate octree)
  std::string search = "nanoflann";
  double octree_leaf = 0.01;  // metres
  bool full_model = false;    // the whole sampled surface instead of its visible part
};

// An exact nearest-neighbour search for PCL's coherence through nanoflann (a dependency of
// depthtrack already): FLANN's kd-tree behind pcl::search::KdTree spends most of its time in the kernel
// here (6-8x slower), PCL's exact octree 15x; only nearest-K queries are used by the coherence.
class NanoflannSearch : public pcl::search::Search<Point> {
 public:
  NanoflannSearch() : pcl::search::Search<Point>("nanoflann", true) {}
  using pcl::search::Search<Point>::nearestKSearch;
  using pcl::search::Search<Point>::radiusSearch;

  void setInputCloud(const PointCloudConstPtr& cloud, const IndicesConstPtr& indices = IndicesConstPtr()) override {
    if (indices && !indices->empty()) throw InputError("NanoflannSearch: index subsets are not supported");
    input_ = cloud;
    indices_ = indices;
    adaptor_.cloud = cloud.get();
    tree_ = std::make_unique<Tree>(3, adaptor_, nanoflann::KDTreeSingleIndexAdaptorParams(10));
    tree_->buildIndex();
  }
  int nearestKSearch(const Point& point, int k, pcl::Indices& indices, std::vector<float>& squared) const override {
    indices.resize(static_cast<size_t>(k));
    squared.resize(static_cast<size_t>(k));
    std::vector<size_t> found(static_cast<size_t>(k));
    const size_t n = tree_->knnSearch(point.data, static_cast<size_t>(k), found.data(), squared.data());
    for (size_t i = 0; i < n; ++i) indices[i] = static_cast<pcl::index_t>(found[i]);
    indices.resize(n);
    squared.resize(n);
    return static_cast<int>(n);
  }
  int radiusSearch(const Point&, double, pcl::Indices&, std::vector<float>&, unsigned int) const override {
    throw InputError("NanoflannSearch: radius search is not implemented (PCL's coherence does not use it)");
  }

 private:
  struct Adaptor {
    const Cloud* cloud = nullptr;
    size_t kdtree_get_point_count() const { return cloud->size(); }
    float kdtree_get_pt(size_t i, size_t dim) const { return (*cloud)[i].data[dim]; }
    template <class Box>
    bool kdtree_get_bbox(Box&) const {
      return false;
    }
  };
  using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, Adaptor>, Adaptor, 3, size_t>;
  Adaptor adaptor_;
  std::unique_ptr<Tree> tree_;
};

// Area-weighted samples of the mesh surface in the object frame, each with its face's normal.
Cloud sample_surface(const Mesh& mesh, int count, uint64_t seed) {
  std::vector<double> cumulative;
  double total = 0;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3f a = mesh.vertices[t[0]], b = mesh.vertices[t[1]], c = mesh.vertices[t[2]];
    total += 0.5 * (b - a).cross(c - a).norm();
    cumulative.push_back(total);
  }
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  Cloud cloud;
  for (int i = 0; i < count; ++i) {
    const size_t k = static_cast<size_t>(std::lower_bound(cumulative.begin(), cumulative.end(), uniform(rng) * total) -
                                         cumulative.begin());
    const auto& t = mesh.triangles[std::min(k, mesh.triangles.size() - 1)];
    const Eigen::Vector3f a = mesh.vertices[t[0]], b = mesh.vertices[t[1]], c = mesh.vertices[t[2]];
    double r1 = std::sqrt(uniform(rng)), r2 = uniform(rng);
    const Eigen::Vector3f p =
        static_cast<float>(1 - r1) * a + static_cast<float>(r1 * (1 - r2)) * b + static_cast<float>(r1 * r2) * c;
    const Eigen::Vector3f n = (b - a).cross(c - a).normalized();
    Point q;
    q.getVector3fMap() = p;
    q.getNormalVector3fMap() = n;
    q.curvature = 0;
    cloud.push_back(q);
  }
  return cloud;
}

// The samples the camera sees at pose (within tolerance of the rendered depth at their pixel),
// moved into the tracker's frame (origin at the mesh centre), normals turned towards the camera.
Cloud visible_samples(const Cloud& samples, const reference::Rasterizer& rasterizer, std::vector<float>& depth,
                      const Pose& pose, const Eigen::Vector3f& centre, double tolerance, bool all) {
  const Camera& cam = rasterizer.camera();
  if (!all) rasterizer.render(pose, depth);
  const Eigen::Matrix3f r = pose.rotation.toRotationMatrix().cast<float>();
  const Eigen::Vector3f t = pose.translation.cast<float>();
  Cloud out;
  for (const Point& s : samples) {
    const Eigen::Vector3f p = r * s.getVector3fMap() + t;
    if (!all) {
      const Eigen::Vector2d uv = cam.project(p.cast<double>());
      const int u = static_cast<int>(std::lround(uv.x())), v = static_cast<int>(std::lround(uv.y()));
      if (u < 0 || v < 0 || u >= cam.width || v >= cam.height) continue;
      const float z = depth[static_cast<size_t>(v) * cam.width + u];
      if (z <= 0 || std::abs(p.z() - z) > tolerance) continue;
    }
    Point q = s;
    q.getVector3fMap() = s.getVector3fMap() - centre;
    if ((r * s.getNormalVector3fMap()).dot(p) > 0) q.getNormalVector3fMap() = -s.getNormalVector3fMap();
    out.push_back(q);
  }
  return out;
}

// Valid pixels of the depth image back-projected, cropped to a sphere; normals from the
// neighbouring pixels (a point without two valid neighbours per axis gets none and is dropped
// when normals are used).
Cloud observed_cloud(const DepthImage& depth, const Camera& cam, const Eigen::Vector3f& centre, double radius,
                     bool need_normals) {
  auto point = [&](int u, int v) -> std::optional<Eigen::Vector3f> {
    if (u < 0 || v < 0 || u >= depth.width() || v >= depth.height() || !DepthImage::is_valid(depth.at(u, v)))
      return std::nullopt;
    return cam.back_project(u, v, depth.at(u, v)).cast<float>();
  };
  Cloud cloud;
  for (int v = 0; v < depth.height(); ++v)
    for (int u = 0; u < depth.width(); ++u) {
      const auto p = point(u, v);
      if (!p || (*p - centre).norm() > radius) continue;
      Point q;
      q.getVector3fMap() = *p;
      q.getNormalVector3fMap().setZero();
      q.curvature = 0;
      if (need_normals) {
        const auto l = point(u - 1, v), r = point(u + 1, v), d = point(u, v - 1), w = point(u, v + 1);
        if (!l || !r || !d || !w) continue;
        Eigen::Vector3f n = (*r - *l).cross(*w - *d);
        if (n.norm() < 1e-12f) continue;
        n.normalize();
        if (n.dot(*p) > 0) n = -n;
        q.getNormalVector3fMap() = n;
      }
      cloud.push_back(q);
    }
  return cloud;
}

Eigen::Affine3f to_affine(const Pose& p) {
  Eigen::Affine3f a = Eigen::Affine3f::Identity();
  a.linear() = p.rotation.toRotationMatrix().cast<float>();
  a.translation() = p.translation.cast<float>();
  return a;
}

Pose to_pose(const Eigen::Affine3f& a) {
  const Eigen::Matrix3d r = a.linear().cast<double>();
  return Pose(a.translation().cast<double>(), Eigen::Quaterniond(r));
}

std::shared_ptr<PclTracker> make_tracker(const Options& o, const Pose& start_about_centre) {
  auto tracker = std::make_shared<PclTracker>(o.threads);
  const auto noise = cli::parse_numbers(o.step_noise, 2, "--step-noise");
  const auto spread = cli::parse_numbers(o.init_spread, 2, "--init-spread");
  const double sm = noise[0] * noise[0], sr = std::pow(noise[1] * kDegree, 2);
  const double im = spread[0] * spread[0], ir = std::pow(spread[1] * kDegree, 2);
  // PCL's "covariances" are per-axis variances (its sampler takes their square roots).
  tracker->setStepNoiseCovariance({sm, sm, sm, sr, sr, sr});
  tracker->setInitialNoiseCovariance({im, im, im, ir, ir, ir});
  tracker->setInitialNoiseMean(std::vector<double>(6, 0.0));
  State bin;
  bin.x = bin.y = bin.z = static_cast<float>(o.bin_size);
  bin.roll = bin.pitch = bin.yaw = static_cast<float>(o.bin_size);
  tracker->setBinSize(bin);
  tracker->setMaximumParticleNum(static_cast<unsigned>(o.max_particles));
  tracker->setEpsilon(o.epsilon);
  tracker->setDelta(o.delta);
  tracker->setParticleNum(o.particles);
  tracker->setIterationNum(1);
  tracker->setResampleLikelihoodThr(0.0);
  tracker->setUseNormal(false);
  tracker->setAlpha(o.alpha);
  tracker->setMotionRatio(o.motion_ratio);
  tracker->setTrans(to_affine(start_about_centre));

  // The nearest observed point of each model point: exact through nanoflann ("nanoflann"), FLANN's
  // kd-tree ("kdtree") or PCL's octree ("octree"), or PCL's approximate octree search ("approx":
  // a point of the nearest 1 cm leaf).
  using Coherence = pcl::tracking::NearestPairPointCloudCoherence<Point>;
  std::shared_ptr<Coherence> coherence;
  if (o.search == "approx") {
    coherence = std::make_shared<pcl::tracking::ApproxNearestPairPointCloudCoherence<Point>>();
  } else if (o.search == "nanoflann") {
    coherence = std::make_shared<Coherence>();
    coherence->setSearchMethod(std::make_shared<NanoflannSearch>());
  } else if (o.search == "kdtree") {
    coherence = std::make_shared<Coherence>();
    coherence->setSearchMethod(std::make_shared<pcl::search::KdTree<Point>>(false));
  } else if (o.search == "octree") {
    coherence = std::make_shared<Coherence>();
    coherence->setSearchMethod(std::make_shared<pcl::search::Octree<Point>>(o.octree_leaf));
  } else {
    throw InputError("--search must be nanoflann, kdtree, octree or approx, got '" + o.search + "'");
  }
  auto distance = std::make_shared<pcl::tracking::DistanceCoherence<Point>>();
  distance->setWeight(1.0 / (o.distance_sigma * o.distance_sigma));
  coherence->addPointCoherence(distance);
  if (o.normal_weight > 0) {
    auto normal = std::make_shared<pcl::tracking::NormalCoherence<Point>>();
    normal->setWeight(o.normal_weight);
    coherence->addPointCoherence(normal);
  }
  coherence->setMaximumDistance(o.max_distance);
  tracker->setCloudCoherence(coherence);
  return tracker;
}

double effective_sample_size(const pcl::PointCloud<State>& particles) {
  double sum = 0, squares = 0;
  for (const State& p : particles) {
    sum += p.weight;
    squares += static_cast<double>(p.weight) * p.weight;
  }
  return squares > 0 ? sum * sum / squares : 0.0;
}

void run(const Options& o) {
  if (o.particles < 1 || o.max_particles < o.particles)
    throw InputError("--particles must be >= 1 and <= --max-particles");
  if (o.samples < 10) throw InputError("--samples must be at least 10");
  const peers::PeerInput in = peers::load_peer_input(o.common);
  const Mesh& mesh = in.mesh;
  const Sequence& seq = in.sequence;
  const int factor = in.factor;
  const Camera& cam = in.camera;
  // Visibility is decided at twice the working resolution where the sensor allows it.
  const Camera vis_cam = seq.camera.decimated(factor % 2 == 0 ? factor / 2 : factor);
  const reference::Rasterizer rasterizer(mesh, vis_cam, 0.05, 6.0);
  std::vector<float> vis_depth(static_cast<size_t>(vis_cam.pixel_count()));

  const Eigen::Vector3f centre = mesh.centre();
  const Pose& start = in.start;
  const Pose centre_offset(centre.cast<double>(), Eigen::Quaterniond::Identity());
  auto tracker = make_tracker(o, start * centre_offset);
  const Cloud samples = sample_surface(mesh, o.samples, o.common.seed);

  Pose estimate = start;
  std::vector<TrackedFrame> frames;
  double particle_sum = 0;
  const auto begin = std::chrono::steady_clock::now();
  for (size_t i = 0; i < seq.frames.size(); ++i) {
    const DepthImage depth = seq.load_depth(i).decimated(factor);
    const Eigen::Vector3f roi_centre = estimate.apply(centre.cast<double>()).cast<float>();
    auto input = std::make_shared<Cloud>(
        observed_cloud(depth, cam, roi_centre, mesh.radius() + o.roi_margin, o.normal_weight > 0));
    auto model = std::make_shared<Cloud>(
        visible_samples(samples, rasterizer, vis_depth, estimate, centre, o.visible_tolerance, o.full_model));
    if (input->empty() || model->empty()) {
      std::fprintf(stderr, "pcl_tracking: frame %s: %zu observed and %zu model points: keeping the estimate\n",
                   seq.frames[i].name.c_str(), input->size(), model->size());
    } else {
      tracker->setReferenceCloud(model);
      tracker->setInputCloud(input);
      tracker->compute();
      estimate = to_pose(tracker->toEigenMatrix(tracker->getResult())) * centre_offset.inverse();
    }
    frames.push_back(peers::tracked_frame(
        seq.frames[i], estimate, tracker->getParticles() ? effective_sample_size(*tracker->getParticles()) : 0));
    particle_sum += tracker->getParticles() ? static_cast<double>(tracker->getParticles()->size()) : 0;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  peers::write_peer_result(o.common.out, frames, seconds);
  std::printf("mean particles %.0f (KLD-adaptive, %d..%d), %zu model samples\n",
              particle_sum / static_cast<double>(frames.size()), o.particles, o.max_particles, samples.size());
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app("Track an object with PCL's KLD-adaptive particle filter on depthtrack's sequences");
  peers::add_peer_options(app, o.common, "Seed of the start perturbation (as depthtrack's --seed) and of the model samples");
  app.add_option("--init-spread", o.init_spread, "Initial particle spread \"METRES DEGREES\" per axis")
      ->capture_default_str();
  app.add_option("--step-noise", o.step_noise, "Per-frame motion noise \"METRES DEGREES\" per axis")
      ->capture_default_str();
  app.add_option("--particles", o.particles, "Initial particle count")->capture_default_str();
  app.add_option("--max-particles", o.max_particles, "KLD-adaptive upper bound")->capture_default_str();
  app.add_option("--bin-size", o.bin_size, "KLD histogram cell (metres and radians)")->capture_default_str();
  app.add_option("--epsilon", o.epsilon, "KLD bound epsilon")->capture_default_str();
  app.add_option("--delta", o.delta, "KLD bound delta")->capture_default_str();
  app.add_option("--samples", o.samples, "Points sampled on the mesh surface")->capture_default_str();
  app.add_option("--max-distance", o.max_distance, "Coherence cut-off (metres)")->capture_default_str();
  app.add_option("--distance-sigma", o.distance_sigma, "DistanceCoherence scale (metres)")->capture_default_str();
  app.add_option("--normal-weight", o.normal_weight, "NormalCoherence weight, 0 = off")->capture_default_str();
  app.add_option("--search", o.search,
                 "Nearest pairs: nanoflann, kdtree or octree (exact), approx (PCL's approximate octree)")
      ->capture_default_str();
  app.add_option("--octree-leaf", o.octree_leaf, "Octree leaf size (metres)")->capture_default_str();
  app.add_option("--roi-margin", o.roi_margin, "ROI sphere: mesh radius plus this (metres)")->capture_default_str();
  app.add_option("--visible-tolerance", o.visible_tolerance, "Model point visible within this of the rendered depth")
      ->capture_default_str();
  app.add_flag("--full-model", o.full_model, "Use every surface sample, not only those visible at the estimate");
  app.add_option("--alpha", o.alpha, "PCL's weight sharpness alpha")->capture_default_str();
  app.add_option("--motion-ratio", o.motion_ratio, "Share of particles moved by the last motion")
      ->capture_default_str();
  app.add_option("--threads", o.threads, "OpenMP threads of the tracker")->capture_default_str();
  return peers::run_peer_program(app, argc, argv, "pcl_tracking", [&] { run(o); });
}
