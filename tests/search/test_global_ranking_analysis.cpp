// Analysis, not a test (hidden: run with "[.analysis]", RANKING_OBJECT=<name> for one object): the no-hint
// search's candidates on ycbv-0000's first frame (reference, 80x60), each unfitted and fitted, with
// its per-pixel classes (visible, occluded = seen in front, contradicted = seen behind, missing) and
// its outline's (past the edge, missing, nearer surface, flush), against the truth. RANKING_WHERE=1 lists
// the outline pixels, RANKING_MAP=",truth,c2 fit," draws the named poses' maps. The candidates (minutes of
// search per object) are cached in the build's test tmp folder; delete the file to search again.
#include <catch2/catch.hpp>
#include <cstdio>
#include <depthtrack/evaluation.hpp>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "model/occlusion_chain.hpp"
#include "reference/observation_model.hpp"
#include "reference/pose_refiner.hpp"
#include "support.hpp"
#include "tracker/make_filter_backend.hpp"
#include "tracker/track_supervisor.hpp"

using namespace depthtrack;

namespace {
void classes(const reference::Rasterizer& r, const TrackerConfig& c, const Pose& pose, const DepthImage& depth,
             const char* label, double adds, double score) {
  std::vector<float> s(static_cast<size_t>(r.camera().pixel_count()));
  const reference::PixelBox box = r.render(pose, s);
  const int w = r.camera().width, h = r.camera().height;
  int vis = 0, occ = 0, con = 0, mis = 0;
  double ll_mid = 0;
  for (int v = box.v0; v < box.v1; ++v)
    for (int u = box.u0; u < box.u1; ++u) {
      const size_t k = static_cast<size_t>(v * w + u);
      if (s[k] <= 0) continue;
      const float y = depth.data()[k];
      if (!DepthImage::is_valid(y)) {
        ++mis;
        continue;
      }
      const double band = c.loss.pixel_sigmas * reference::depth_sigma(c.observation, y);
      ll_mid += reference::pixel_log_ratio(reference::pixel_densities(c.observation, y, s[k]), 0.5);
      if (y < s[k] - band)
        ++occ;
      else if (y > s[k] + band)
        ++con;
      else
        ++vis;
    }
  int out = 0, past = 0, nearer = 0, flush = 0, none = 0;
  std::string where;
  for (int v = box.v0; v < box.v1; ++v)
    for (int u = box.u0; u < box.u1; ++u) {
      const double yh = s[static_cast<size_t>(v * w + u)];
      if (yh <= 0) continue;
      const int du[4] = {1, -1, 0, 0}, dv[4] = {0, 0, 1, -1};
      for (int n = 0; n < 4; ++n) {
        const int nu = u + du[n], nv = v + dv[n];
        if (nu < 0 || nv < 0 || nu >= w || nv >= h) continue;
        const size_t k = static_cast<size_t>(nv * w + nu);
        if (s[k] > 0) continue;
        ++out;
        const float y = depth.data()[k];
        const double band = c.loss.pixel_sigmas * reference::depth_sigma(c.observation, y);
        char ch;
        if (!DepthImage::is_valid(y)) {
          ++none;
          ch = 'm';
        } else if (y > yh + band) {
          ++past;
          ch = 'p';
        } else if (y < yh - band) {
          ++nearer;
          ch = 'n';
        } else {
          ++flush;
          ch = 'f';
        }
        char buf[32];
        std::snprintf(buf, sizeof buf, " %d,%d%c", nu, nv, ch);
        where += buf;
      }
    }
  std::printf(
      "%-10s adds %6.1f mm score %7.1f | px %3d vis %3d occ %3d con %3d mis %3d | ll(p=.5) %7.1f | outline %3d past "
      "%3d "
      "none %3d nearer %3d flush %3d | sep %.2f sep_not_nearer %.2f\n",
      label, 1000 * adds, score, vis + occ + con + mis, vis, occ, con, mis, ll_mid, out, past, none, nearer, flush,
      out ? double(past + none) / out : 0, (out - nearer) ? double(past + none) / (out - nearer) : 0);
  if (std::getenv("RANKING_WHERE")) std::printf("   outline:%s\n", where.c_str());
  if (std::getenv("RANKING_MAP") &&
      std::string(std::getenv("RANKING_MAP")).find(std::string(",") + label + ",") != std::string::npos) {
    // Silhouette: V visible, O occluded (seen in front), C contradicted (seen behind), M missing;
    // outline: p past the edge, m missing, n nearer surface, f flush; elsewhere the depth in dm.
    std::vector<char> map(static_cast<size_t>(w * h), 0);
    for (int v = 0; v < h; ++v)
      for (int u = 0; u < w; ++u) {
        const size_t k = static_cast<size_t>(v * w + u);
        const float y = depth.data()[k];
        const double band = c.loss.pixel_sigmas * reference::depth_sigma(c.observation, y);
        if (s[k] > 0) {
          map[k] = !DepthImage::is_valid(y) ? 'M' : y < s[k] - band ? 'O' : y > s[k] + band ? 'C' : 'V';
          continue;
        }
        double yh = 0;
        const int du[4] = {1, -1, 0, 0}, dv[4] = {0, 0, 1, -1};
        for (int n = 0; n < 4; ++n) {
          const int nu = u + du[n], nv = v + dv[n];
          if (nu < 0 || nv < 0 || nu >= w || nv >= h) continue;
          const double z = s[static_cast<size_t>(nv * w + nu)];
          if (z > 0) yh = z;
        }
        if (yh > 0)
          map[k] = !DepthImage::is_valid(y) ? 'm' : y > yh + band ? 'p' : y < yh - band ? 'n' : 'f';
        else
          map[k] = DepthImage::is_valid(y) ? static_cast<char>('0' + std::min(9, int(y * 10) % 10)) : ' ';
      }
    for (int v = 0; v < h; ++v) std::printf("   %2d %.*s\n", v, w, &map[static_cast<size_t>(v * w)]);
  }
}
}  // namespace

TEST_CASE("no-hint candidates on ycbv-0000, analysed", "[.analysis]") {
  const auto clip = test::shared_data("sequences/ycbv-0000/gt.json");
  if (!clip) return;
  const char* only = std::getenv("RANKING_OBJECT");
  for (const std::string name : {"009_gelatin_box", "025_mug", "061_foam_brick"}) {
    if (only && name != only) continue;
    const auto mesh_path = test::shared_data("meshes/ycb/" + name + ".obj");
    if (!mesh_path) continue;
    const Mesh mesh = Mesh::load(*mesh_path);
    const AddsMetric adds(mesh);
    const Sequence seq = load_sequence(clip->parent_path(), name);
    TrackerConfig config;
    const int dec = seq.camera.decimation_factor_for(config.width, config.height);
    const Camera working = seq.camera.decimated(dec);
    const DepthImage sensor = seq.load_depth(0);
    const DepthImage depth = sensor.decimated(dec);
    const Pose truth = *seq.frames[0].ground_truth;
    auto backend = make_filter_backend(mesh, working, config);
    TrackSupervisor sup(*backend, mesh, seq.camera, working, dec, config);
    const auto cache_dir = std::filesystem::path(DEPTHTRACK_TEST_TMP) / "global_ranking_analysis";
    std::filesystem::create_directories(cache_dir);
    const std::string cache = (cache_dir / (name + ".txt")).string();
    search::SearchResult r;
    std::ifstream in(cache);
    if (in) {
      in >> r.rotation_radius >> r.translation_spacing;
      search::Candidate c;
      while (in >> c.pose.translation.x() >> c.pose.translation.y() >> c.pose.translation.z() >> c.pose.rotation.w() >>
             c.pose.rotation.x() >> c.pose.rotation.y() >> c.pose.rotation.z() >> c.score)
        r.candidates.push_back(c);
    } else {
      r = sup.candidates(sensor, depth, InitHint::anywhere(), 0, 0);
      std::ofstream o(cache);
      o.precision(17);
      o << r.rotation_radius << " " << r.translation_spacing << "\n";
      for (const auto& c : r.candidates)
        o << c.pose.translation.transpose() << " " << c.pose.rotation.w() << " " << c.pose.rotation.x() << " "
          << c.pose.rotation.y() << " " << c.pose.rotation.z() << " " << c.score << "\n";
    }
    if (r.candidates.empty()) continue;
    std::printf("\n== %s: %zu candidates\n", name.c_str(), r.candidates.size());
    reference::Rasterizer ras(mesh, working, config.near_plane, config.observation.max_depth);
    auto full = backend->make_pose_scorer(mesh);
    const auto score = [&](const Pose& p) {
      return full->score(std::span<const Pose>(&p, 1), depth, config.observation)[0];
    };
    classes(ras, config, truth, depth, "truth", 0, score(truth));
    TrackerConfig fc = config;
    fc.refine.iterations = 16;
    reference::PoseRefiner refiner(mesh, working, fc);
    const std::vector<double> fresh(static_cast<size_t>(working.pixel_count()), model::fresh_occlusion(config));
    std::sort(r.candidates.begin(), r.candidates.end(), [](auto& a, auto& b) { return a.score > b.score; });
    for (size_t i = 0; i < r.candidates.size(); ++i) {
      const Pose p = r.candidates[i].pose;
      char l[40];
      std::snprintf(l, sizeof l, "c%zu", i);
      classes(ras, config, p, depth, l, adds(p, truth), r.candidates[i].score);
      if (i < 8) {
        const Pose f = refiner.refine(p, depth, fresh).pose;
        std::snprintf(l, sizeof l, "c%zu fit", i);
        classes(ras, config, f, depth, l, adds(f, truth), score(f));
      }
    }
  }
}
