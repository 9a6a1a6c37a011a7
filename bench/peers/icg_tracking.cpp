// A third peer: ICG, "Iterative Corresponding Geometry" (Stoiber et al., CVPR 2022; DLR-RM/3DObjectTracking,
// MIT), a local fitter (Newton steps with Tikhonov regularisation on correspondences between sparse model
// points and the depth image, optionally also region lines on a colour image; no particles). Run on exactly
// the frames depthtrack reads from exactly its start (bench/peers/peer_run.hpp); writes the CSV
// `depthtrack track` writes.
//
// ICG's library is built outside this repository and linked on request (-DDEPTHTRACK_ICG_DIR,
// bench/peers/CMakeLists.txt). Its tracker needs "sparse viewpoint" models made beforehand by rendering the
// mesh from thousands of directions (OpenGL through GLFW: run under xvfb-run on a headless machine); they
// take minutes per object, so they are kept in --cache-dir, under a name made from the mesh's content and
// reused by every later run (ICG itself regenerates a file whose generation settings differ).
//
// Defaults are ICG's own YCB-Video evaluation settings (examples/evaluate_ycb_dataset.cpp and the models of
// ycb_evaluator.cpp); the options below vary the ones worth varying.
#include <icg/body.h>
#include <icg/camera.h>
#include <icg/depth_modality.h>
#include <icg/depth_model.h>
#include <icg/optimizer.h>
#include <icg/region_modality.h>
#include <icg/region_model.h>
#include <icg/tracker.h>
#include <omp.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <depthtrack/error.hpp>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "peer_run.hpp"

using namespace depthtrack;
namespace fs = std::filesystem;

namespace {

struct Options {
  peers::PeerOptions common;
  std::string modalities = "depth";
  fs::path cache_dir = fs::temp_directory_path() / "depthtrack-icg-models";
  int corr_iterations = 4, update_iterations = 2;  // ICG's YCB-Video tracker settings
  int depth_points = 200;                          // model points the depth modality uses per iteration
  float depth_stride = 0.005f;                     // metres between the depth modality's correspondence probes
  int model_divides = 4;                           // the viewpoint sphere's subdivisions (4: 2,562 views)
  bool culling = true, flip_winding = false;
  int model_threads = 2;
};

// An ICG camera whose image this runner sets before each frame (ICG's own cameras read files or sensors).
// ICG's camera bases have no virtual destructor; these are only ever owned by shared_ptrs made for
// their own type (std::make_shared below), which destroy them as what they are.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnon-virtual-dtor"
class DepthFrame final : public icg::DepthCamera {
 public:
  DepthFrame(const icg::Intrinsics& intrinsics, float metres_per_unit) : icg::DepthCamera("depth_camera") {
    intrinsics_ = intrinsics;
    depth_scale_ = metres_per_unit;
  }
  bool SetUp() override { return set_up_ = true; }
  bool UpdateImage(bool) override { return true; }
  void set_image(cv::Mat image) { image_ = std::move(image); }
};

class ColourFrame final : public icg::ColorCamera {
 public:
  explicit ColourFrame(const icg::Intrinsics& intrinsics) : icg::ColorCamera("colour_camera") {
    intrinsics_ = intrinsics;
  }
  bool SetUp() override { return set_up_ = true; }
  bool UpdateImage(bool) override { return true; }
  void set_image(cv::Mat image) { image_ = std::move(image); }
};
#pragma GCC diagnostic pop

// The decimated depth in ICG's 16-bit form: units of the sequence's own metres_per_unit (exact for the
// sensor images, which are stored in those units), 0 where there is no measurement.
cv::Mat depth_units(const DepthImage& depth, double metres_per_unit) {
  cv::Mat image(depth.height(), depth.width(), CV_16UC1);
  for (int v = 0; v < depth.height(); ++v) {
    auto* row = image.ptr<uint16_t>(v);
    for (int u = 0; u < depth.width(); ++u) {
      const float z = depth.at(u, v);
      const double units = DepthImage::is_valid(z) ? std::round(z / metres_per_unit) : 0.0;
      row[u] = units >= 1 && units <= 65535 ? static_cast<uint16_t>(units) : 0;
    }
  }
  return image;
}

cv::Mat colour_image(const SequenceFrame& frame, const Camera& cam) {
  if (frame.colour_path.empty())
    throw InputError("frame " + frame.name + " has no colour image: use --modalities depth");
  cv::Mat image = cv::imread(frame.colour_path.string(), cv::IMREAD_COLOR);  // BGR, as ICG's cameras give it
  if (image.empty()) throw InputError("cannot read the colour image '" + frame.colour_path.string() + "'");
  if (image.cols != cam.width || image.rows != cam.height)
    cv::resize(image, image, cv::Size(cam.width, cam.height), 0, 0, cv::INTER_AREA);
  return image;
}

icg::Transform3fA to_icg(const Pose& p) {
  icg::Transform3fA t = icg::Transform3fA::Identity();
  t.linear() = p.rotation.toRotationMatrix().cast<float>();
  t.translation() = p.translation.cast<float>();
  return t;
}

Pose from_icg(const icg::Transform3fA& t) {
  const Eigen::Matrix3d r = t.rotation().cast<double>();
  return Pose(t.translation().cast<double>(), Eigen::Quaterniond(r).normalized());
}

bool finite(const icg::Transform3fA& t) {
  return t.matrix().allFinite();
}

// The mesh as the OBJ ICG's Body loads (metres, the mesh's own winding), named by a hash of that text so
// that a cached model is found again for the same mesh and never used for another.
fs::path write_obj(const Mesh& mesh, const std::string& stem, const fs::path& dir) {
  std::ostringstream text;
  text << std::setprecision(9);
  for (const auto& v : mesh.vertices) text << "v " << v.x() << " " << v.y() << " " << v.z() << "\n";
  for (const auto& t : mesh.triangles) text << "f " << t[0] + 1 << " " << t[1] + 1 << " " << t[2] + 1 << "\n";
  const std::string obj = text.str();
  std::ostringstream name;
  name << stem << "-" << std::hex << std::hash<std::string>{}(obj) << ".obj";
  const fs::path path = dir / name.str();
  if (!fs::exists(path)) {
    const fs::path part = path.string() + ".part";
    std::ofstream out(part);
    out << obj;
    if (!out.flush()) throw InputError("cannot write '" + part.string() + "'");
    out.close();
    fs::rename(part, path);  // whole or absent, should two runs make it at once
  }
  return path;
}

void require(bool ok, const std::string& what) {
  if (!ok) throw InputError("ICG could not " + what + " (its message above says why)");
}

void run(const Options& o) {
  const bool region = o.modalities == "depth+region";
  if (!region && o.modalities != "depth")
    throw InputError("--modalities must be depth or depth+region, got '" + o.modalities + "'");
  if (o.corr_iterations < 1 || o.update_iterations < 1)
    throw InputError("--corr-iterations and --update-iterations must be at least 1");
  if (o.depth_points < 1 || !(o.depth_stride > 0))
    throw InputError("--depth-points and --depth-stride must be positive");
  if (o.model_divides < 1 || o.model_threads < 1)
    throw InputError("--model-divides and --model-threads must be at least 1");
  const peers::PeerInput in = peers::load_peer_input(o.common);
  const Camera& cam = in.camera;
  const icg::Intrinsics intrinsics{static_cast<float>(cam.fx),
                                   static_cast<float>(cam.fy),
                                   static_cast<float>(cam.cx),
                                   static_cast<float>(cam.cy),
                                   cam.width,
                                   cam.height};

  fs::create_directories(o.cache_dir);
  const std::string stem = fs::path(o.common.mesh).stem().string();
  const fs::path obj = write_obj(in.mesh, stem, o.cache_dir);
  const std::string key = obj.stem().string() + (o.flip_winding ? "-cw" : "") + (o.culling ? "" : "-noculling") + "-d" +
                          std::to_string(o.model_divides);
  auto body = std::make_shared<icg::Body>(stem, obj, 1.0f, !o.flip_winding, o.culling, icg::Transform3fA::Identity());
  require(body->SetUp(), "load the mesh '" + obj.string() + "'");

  // ICG's YCB-Video models: a 0.8 m viewpoint sphere, 500 points a view, depth offsets up to 5 cm in 2 mm
  // steps, no random seed, 2000x2000 renders. Made with model_threads threads, tracked with one.
  omp_set_num_threads(o.model_threads);
  auto depth_model = std::make_shared<icg::DepthModel>(stem + "_depth_model", body, o.cache_dir / (key + "-depth.bin"),
                                                       0.8f, o.model_divides, 500, 0.05f, 0.002f, false, 2000);
  require(depth_model->SetUp(), "make or load its depth model");
  std::shared_ptr<icg::RegionModel> region_model;
  if (region) {
    region_model = std::make_shared<icg::RegionModel>(stem + "_region_model", body, o.cache_dir / (key + "-region.bin"),
                                                      0.8f, o.model_divides, 500, 0.05f, 0.002f, false, 2000);
    require(region_model->SetUp(), "make or load its region model");
  }
  omp_set_num_threads(1);

  auto depth_camera = std::make_shared<DepthFrame>(intrinsics, static_cast<float>(in.sequence.metres_per_unit));
  auto colour_camera = std::make_shared<ColourFrame>(intrinsics);
  depth_camera->SetUp();
  colour_camera->SetUp();
  auto optimizer = std::make_shared<icg::Optimizer>(stem + "_optimizer");
  if (region) {
    auto r = std::make_shared<icg::RegionModality>(stem + "_region_modality", body, colour_camera, region_model);
    r->set_n_unoccluded_iterations(0);
    r->set_n_lines(200);
    r->set_min_continuous_distance(3.0f);
    r->set_function_length(8);
    r->set_distribution_length(12);
    r->set_function_amplitude(0.43f);
    r->set_function_slope(0.5f);
    r->set_learning_rate(1.3f);
    r->set_scales({7, 4, 2});
    r->set_standard_deviations({25.0f, 15.0f, 10.0f});
    r->set_n_histogram_bins(16);
    r->set_learning_rate_f(0.2f);
    r->set_learning_rate_b(0.2f);
    r->set_unconsidered_line_length(0.5f);
    r->set_max_considered_line_length(20.0f);
    r->set_measured_depth_offset_radius(0.01f);
    r->set_measured_occlusion_radius(0.01f);
    r->set_measured_occlusion_threshold(0.03f);
    r->MeasureOcclusions(depth_camera);
    require(r->SetUp(), "set up its region modality");
    optimizer->AddModality(r);
  }
  auto d = std::make_shared<icg::DepthModality>(stem + "_depth_modality", body, depth_camera, depth_model);
  d->set_n_unoccluded_iterations(0);
  d->set_n_points(o.depth_points);
  d->set_stride_length(o.depth_stride);
  d->set_considered_distances({0.07f, 0.05f, 0.04f});
  d->set_standard_deviations({0.05f, 0.03f, 0.02f});
  d->set_measured_depth_offset_radius(0.01f);
  d->set_measured_occlusion_radius(0.01f);
  d->set_measured_occlusion_threshold(0.03f);
  d->MeasureOcclusions();
  require(d->SetUp(), "set up its depth modality");
  optimizer->AddModality(d);
  optimizer->set_tikhonov_parameter_rotation(1000.0f);
  optimizer->set_tikhonov_parameter_translation(30000.0f);
  require(optimizer->SetUp(), "set up its optimizer");
  icg::Tracker tracker("tracker");
  tracker.AddOptimizer(optimizer);
  tracker.set_n_corr_iterations(o.corr_iterations);
  tracker.set_n_update_iterations(o.update_iterations);
  require(tracker.SetUp(false), "set up its tracker");

  // As ICG's YCB-Video evaluation: the body placed at the start, the modalities started on the first
  // frame, then on every frame (the first too) its correspondence and update iterations.
  Pose estimate = in.start;
  body->set_body2world_pose(to_icg(estimate));
  std::vector<TrackedFrame> frames;
  int failures = 0;
  const auto begin = std::chrono::steady_clock::now();
  for (size_t i = 0; i < in.sequence.frames.size(); ++i) {
    depth_camera->set_image(depth_units(in.sequence.load_depth(i).decimated(in.factor), in.sequence.metres_per_unit));
    if (region) colour_camera->set_image(colour_image(in.sequence.frames[i], cam));
    const int it = static_cast<int>(i);
    bool ok = i > 0 || tracker.StartModalities(0);
    for (int c = 0; ok && c < o.corr_iterations; ++c) {
      ok = tracker.CalculateCorrespondences(it, c);
      for (int u = 0; ok && u < o.update_iterations; ++u)
        ok = tracker.CalculateGradientAndHessian(it, c, u) && tracker.CalculateOptimization(it, c, u);
    }
    ok = ok && tracker.CalculateResults(it) && finite(body->body2world_pose());
    if (ok) {
      estimate = from_icg(body->body2world_pose());
    } else {  // keep the last pose and start from it again, as the ViSP runner does
      ++failures;
      std::fprintf(stderr, "icg_tracking: frame %s failed: keeping the estimate\n", in.sequence.frames[i].name.c_str());
      body->set_body2world_pose(to_icg(estimate));
      tracker.StartModalities(it);
    }
    frames.push_back(peers::tracked_frame(in.sequence.frames[i], estimate, NAN));
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  peers::write_peer_result(o.common.out, frames, seconds);
  std::printf("ICG %s, %d x %d iterations, %d frames failed\n", o.modalities.c_str(), o.corr_iterations,
              o.update_iterations, failures);
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app("Track an object with ICG (Iterative Corresponding Geometry) on depthtrack's sequences");
  peers::add_peer_options(app, o.common, "Seed of the start perturbation (as depthtrack's --seed)");
  app.add_option("--modalities", o.modalities, "depth, or depth+region (needs the sequence's colour images)")
      ->capture_default_str();
  app.add_option("--cache-dir", o.cache_dir, "Folder of ICG's generated models, reused between runs")
      ->capture_default_str();
  app.add_option("--corr-iterations", o.corr_iterations, "Correspondence searches per frame")->capture_default_str();
  app.add_option("--update-iterations", o.update_iterations, "Pose updates per correspondence search")
      ->capture_default_str();
  app.add_option("--depth-points", o.depth_points, "Model points the depth modality uses")->capture_default_str();
  app.add_option("--depth-stride", o.depth_stride, "Metres between the depth modality's correspondence probes")
      ->capture_default_str();
  app.add_option("--model-divides", o.model_divides, "Subdivisions of the model's viewpoint sphere")
      ->capture_default_str();
  app.add_option("--model-threads", o.model_threads, "Threads that make a missing model")->capture_default_str();
  app.add_option("--culling", o.culling, "Back-face culling when the models are rendered (off for open meshes)")
      ->capture_default_str();
  app.add_flag("--flip-winding", o.flip_winding, "Take the mesh's triangles as clockwise");
  return peers::run_peer_program(app, argc, argv, "icg_tracking", [&] { run(o); });
}
