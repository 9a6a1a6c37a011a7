// The other peer users pick instead of depthtrack: ViSP's model-based tracker (vpMbGenericTracker)
// with its depth features alone, a local fitter (Gauss-Newton on the depth's point-to-plane
// residuals, a robust M-estimator, no particles). Run on exactly the frames depthtrack reads from
// exactly its start (bench/peers/peer_run.hpp); writes the CSV `depthtrack track` writes.
//
// ViSP reads models as CAO or VRML, not meshes: the mesh (simplified as depthtrack's tracker draws
// it, TrackerConfig::simplify_error) is written as a CAO file of triangles, one face each. Features:
// "dense" (every sampled pixel's distance to its face's plane, vpMbDepthDenseTracker) or "normal"
// (each face's plane fitted to its pixels, vpMbDepthNormalTracker).
#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpColVector.h>
#include <visp3/core/vpException.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/mbt/vpMbGenericTracker.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <depthtrack/error.hpp>
#include <depthtrack/tracker_config.hpp>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>

#include "core/mesh_simplify.hpp"
#include "peer_run.hpp"

using namespace depthtrack;

namespace {

struct Options {
  peers::PeerOptions common;
  double simplify_error = TrackerConfig{}.simplify_error;
  std::string features = "dense";
  unsigned sampling_step = 1;  // every pixel at the working resolution (ViSP's default 2 is for 640x480)
  unsigned max_iterations = 30;
  double gain = 1.0;
  double near = 0.05, far = 6.0;  // metres: depthtrack's rasterizer's planes
  bool scanline = true;           // ViSP's own visibility test, for concave meshes (the mug's handle)
  bool flip_winding = false;
};

// The mesh as a ViSP CAO (version 1) model: its points, then each triangle as a face of three.
// The meshes' own (outward) winding is what ViSP's visibility test takes as facing the camera
// (checked on the handset and the castle: flipped, every frame fails).
std::filesystem::path write_cao(const Mesh& mesh, bool flip) {
  const auto path =
      std::filesystem::temp_directory_path() /
      ("depthtrack-visp-" + std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()) + ".cao");
  std::ofstream out(path);
  if (!out) throw InputError("cannot write the ViSP model '" + path.string() + "'");
  out.precision(9);
  out << "V1\n# points\n" << mesh.vertices.size() << "\n";
  for (const auto& v : mesh.vertices) out << v.x() << " " << v.y() << " " << v.z() << "\n";
  out << "# lines\n0\n# faces from lines\n0\n# faces from points\n" << mesh.triangles.size() << "\n";
  for (const auto& t : mesh.triangles)
    out << "3 " << t[0] << " " << (flip ? t[2] : t[1]) << " " << (flip ? t[1] : t[2]) << "\n";
  out << "# cylinders\n0\n# circles\n0\n";
  if (!out) throw InputError("cannot write the ViSP model '" + path.string() + "'");
  return path;
}

vpHomogeneousMatrix to_visp(const Pose& p) {
  vpHomogeneousMatrix m;
  const Eigen::Matrix3d r = p.rotation.toRotationMatrix();
  for (unsigned i = 0; i < 3; ++i) {
    for (unsigned j = 0; j < 3; ++j) m[i][j] = r(i, j);
    m[i][3] = p.translation[i];
  }
  return m;
}

bool finite(const vpHomogeneousMatrix& m) {
  for (unsigned i = 0; i < 3; ++i)
    for (unsigned j = 0; j < 4; ++j)
      if (!std::isfinite(m[i][j])) return false;
  return true;
}

Pose from_visp(const vpHomogeneousMatrix& m) {
  Eigen::Matrix3d r;
  Eigen::Vector3d t;
  for (unsigned i = 0; i < 3; ++i) {
    for (unsigned j = 0; j < 3; ++j) r(i, j) = m[i][j];
    t[i] = m[i][3];
  }
  return Pose(t, Eigen::Quaterniond(r).normalized());
}

// The depth back-projected per pixel, as ViSP's depth trackers take it: an organized cloud, a pixel
// without depth at the origin (ViSP skips points at or behind z = 0). The cloud's vectors are made on the
// first frame only and overwritten after: a heap vector per pixel each frame would be timed as ViSP's.
void fill_cloud(const DepthImage& depth, const Camera& cam, std::vector<vpColVector>& cloud) {
  cloud.resize(static_cast<size_t>(cam.width) * cam.height, vpColVector(3, 0.0));
  for (int v = 0; v < cam.height; ++v)
    for (int u = 0; u < cam.width; ++u) {
      const float z = depth.at(u, v);
      const Eigen::Vector3d p = DepthImage::is_valid(z) ? cam.back_project(u, v, z) : Eigen::Vector3d::Zero();
      vpColVector& q = cloud[static_cast<size_t>(v) * cam.width + u];
      q[0] = p.x();
      q[1] = p.y();
      q[2] = p.z();
    }
}

int tracker_type(const std::string& features) {
  if (features == "dense") return vpMbGenericTracker::DEPTH_DENSE_TRACKER;
  if (features == "normal") return vpMbGenericTracker::DEPTH_NORMAL_TRACKER;
  throw InputError("--features must be dense or normal, got '" + features + "'");
}

void run(const Options& o) {
  if (o.sampling_step < 1) throw InputError("--sampling-step must be at least 1");
  const peers::PeerInput in = peers::load_peer_input(o.common);
  const Mesh model = simplify_for_drawing(in.mesh, o.simplify_error).mesh;
  const Camera& cam = in.camera;

  vpMbGenericTracker tracker(1, tracker_type(o.features));
  tracker.setCameraParameters(vpCameraParameters(cam.fx, cam.fy, cam.cx, cam.cy));
  tracker.setNearClippingDistance(o.near);
  tracker.setFarClippingDistance(o.far);
  tracker.setClipping(vpPolygon3D::NEAR_CLIPPING | vpPolygon3D::FAR_CLIPPING);
  tracker.setScanLineVisibilityTest(o.scanline);
  tracker.setMaxIter(o.max_iterations);
  tracker.setLambda(o.gain);
  if (o.features == "dense")
    tracker.setDepthDenseSamplingStep(o.sampling_step, o.sampling_step);
  else
    tracker.setDepthNormalSamplingStep(o.sampling_step, o.sampling_step);
  const auto cao = write_cao(model, o.flip_winding);
  try {
    tracker.loadModel(cao.string());
  } catch (...) {
    std::filesystem::remove(cao);
    throw;
  }
  std::filesystem::remove(cao);

  const vpImage<unsigned char> image(static_cast<unsigned>(cam.height), static_cast<unsigned>(cam.width), 0);
  tracker.initFromPose(image, to_visp(in.start));
  const std::string camera_name = tracker.getCameraNames().front();
  std::map<std::string, const vpImage<unsigned char>*> images{{camera_name, &image}};
  std::vector<vpColVector> cloud;
  std::map<std::string, const std::vector<vpColVector>*> clouds{{camera_name, &cloud}};
  std::map<std::string, unsigned> widths{{camera_name, static_cast<unsigned>(cam.width)}};
  std::map<std::string, unsigned> heights{{camera_name, static_cast<unsigned>(cam.height)}};

  Pose estimate = in.start;
  std::vector<TrackedFrame> frames;
  int failures = 0;
  const auto begin = std::chrono::steady_clock::now();
  for (size_t i = 0; i < in.sequence.frames.size(); ++i) {
    fill_cloud(in.sequence.load_depth(i).decimated(in.factor), cam, cloud);
    try {
      tracker.track(images, clouds, widths, heights);
      vpHomogeneousMatrix pose;
      tracker.getPose(pose);
      if (!finite(pose)) throw vpException(vpException::fatalError, "the fit returned a pose that is not finite");
      estimate = from_visp(pose);
    } catch (const vpException& e) {  // too few features, or diverged: keep the last pose, start from it again
      ++failures;
      std::fprintf(stderr, "visp_tracking: frame %s: %s: keeping the estimate\n", in.sequence.frames[i].name.c_str(),
                   e.what());
      tracker.initFromPose(image, to_visp(estimate));
    }
    frames.push_back(peers::tracked_frame(in.sequence.frames[i], estimate, NAN));
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  peers::write_peer_result(o.common.out, frames, seconds);
  std::printf("%zu model faces, %s features, %d frames failed\n", model.triangles.size(), o.features.c_str(), failures);
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app("Track an object with ViSP's model-based tracker on its depth features, on depthtrack's sequences");
  peers::add_peer_options(app, o.common, "Seed of the start perturbation (as depthtrack's --seed)");
  app.add_option("--simplify-error", o.simplify_error, "Mesh simplified within this (metres) before it becomes faces")
      ->capture_default_str();
  app.add_option("--features", o.features, "dense (per-pixel point-to-plane) or normal (per-face plane)")
      ->capture_default_str();
  app.add_option("--sampling-step", o.sampling_step, "Use every Nth pixel in x and y")->capture_default_str();
  app.add_option("--max-iterations", o.max_iterations, "Gauss-Newton iterations per frame")->capture_default_str();
  app.add_option("--gain", o.gain, "Gauss-Newton step gain (ViSP's lambda)")->capture_default_str();
  app.add_option("--scanline", o.scanline, "ViSP's scan-line visibility test (concave meshes)")->capture_default_str();
  app.add_flag("--flip-winding", o.flip_winding, "Write the faces with the opposite winding");
  return peers::run_peer_program(app, argc, argv, "visp_tracking", [&] { run(o); });
}
