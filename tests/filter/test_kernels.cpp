// Each kernel under cl/ against the reference function it implements, on the test device.
#include <algorithm>
#include <catch2/catch.hpp>
#include <random>

#include "compute/buffer.hpp"
#include "compute/kernel_sources.hpp"
#include "compute/program_cache.hpp"
#include "device_support.hpp"
#include "dt_atlas.h"
#include "dt_params.h"
#include "dt_state.h"
#include "dt_summary.h"
#include "dt_time_index.h"
#include "filter/wide_summary.hpp"
#include "model/occlusion_chain.hpp"
#include "model/particle.hpp"
#include "model/particle_packing.hpp"
#include "philox.h"
#include "reference/observation_model.hpp"
#include "reference/pose_mean.hpp"
#include "reference/pose_refiner.hpp"
#include "reference/rasterizer.hpp"
#include "reference/weights.hpp"

using namespace depthtrack;

namespace {
constexpr unsigned kGroup = 128;

std::unique_ptr<compute::Program> build(compute::Queue& q, const std::string& file, int occlusion_mode = 0) {
  return q.build(file, compute::kernel_source(file),
                 {"DT_GROUP_SIZE=" + std::to_string(kGroup), "DT_OCCLUSION=" + std::to_string(occlusion_mode)});
}

model::ParticleState random_state(std::mt19937& rng) {
  std::normal_distribution<double> n;
  model::ParticleState s;
  s.pose =
      Pose({0.05 * n(rng), 0.05 * n(rng), 0.8 + 0.05 * n(rng)}, rotation_exp(Eigen::Vector3d(n(rng), n(rng), n(rng))));
  s.linear_velocity = Eigen::Vector3d(0.1 * n(rng), 0.1 * n(rng), 0.1 * n(rng));
  s.angular_velocity = Eigen::Vector3d(n(rng), n(rng), n(rng));
  return s;
}

dt_model model_args() {
  const ObservationModel o;
  const OcclusionModel c;
  return {static_cast<float>(o.sigma_constant),
          static_cast<float>(o.sigma_quadratic),
          static_cast<float>(o.tail_weight / o.max_depth),
          static_cast<float>(1 - o.tail_weight),
          static_cast<float>(o.occluder_rate),
          static_cast<float>(std::log(0.6)),
          0.25f};
}
}  // namespace

TEST_CASE("propagate kernel equals the reference motion step", "[device][kernels]") {
  if (!test::device_available()) return;
  auto q = compute::open_device(test::device_selector());
  auto program = build(*q, "propagate.cl");
  auto kernel = program->kernel("propagate");
  std::mt19937 rng(3);
  std::vector<model::ParticleState> states(100);
  for (auto& s : states) s = random_state(rng);
  compute::Buffer<float> buffer(*q, states.size() * DT_STATE_STRIDE);
  buffer.upload(pack_particles(states));
  const Eigen::Vector3d centre(0.01, -0.02, 0.03);
  const MotionModel m;
  const double dt = 0.05, keep = std::pow(m.damping, dt * m.reference_rate);
  const double spread = std::sqrt((1 - keep * keep) / (1 - m.damping * m.damping));
  const dt_motion args{static_cast<float>(keep),
                       static_cast<float>(m.sigma_linear * 30 * spread),
                       static_cast<float>(m.sigma_angular * 30 * spread),
                       static_cast<float>(dt),
                       0.01f,
                       -0.02f,
                       0.03f};
  const uint64_t seed = 0x123456789ull;
  q->launch(*kernel, compute::NdRange::linear(128, 64), buffer, static_cast<unsigned>(states.size()),
            static_cast<unsigned>(seed & 0xffffffffu), static_cast<unsigned>(seed >> 32), 7u, args)
      ->wait();
  const auto out = buffer.download();
  for (size_t i = 0; i < states.size(); ++i) {
    float n[6];
    dt_normals6(seed, static_cast<dt_u32>(i), 7, DT_STREAM_MOTION, n);
    model::propagate_particle(states[i], model::motion_step(m, dt), centre, n);
    const float* p = out.data() + i * DT_STATE_STRIDE;
    const Pose got({p[DT_TX], p[DT_TX + 1], p[DT_TX + 2]},
                   Eigen::Quaterniond(p[DT_QW], p[DT_QW + 1], p[DT_QW + 2], p[DT_QW + 3]));
    REQUIRE(translation_error(got, states[i].pose) < 2e-6);
    REQUIRE(rotation_error(got, states[i].pose) < 2e-5);
    REQUIRE(p[DT_WX + 1] == Approx(states[i].angular_velocity.y()).epsilon(1e-5).margin(1e-6));
  }
}

TEST_CASE("weigh kernel equals the reference per-pixel sum and occlusion updates", "[device][kernels]") {
  if (!test::device_available()) return;
  auto q = compute::open_device(test::device_selector());
  const Camera camera = Camera::make(80, 60, 65.625, 65.625, 39.9375, 29.9375);
  const Mesh mesh = builtin_demo_mesh();
  const size_t pixels = 4800, count = 16;
  reference::Rasterizer r(mesh, camera, 0.05, 6.0);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  // Observed: the object at a pose, with an occluding band, missing pixels and a wall.
  std::vector<float> observed(pixels);
  const Pose truth({0, 0, 0.8}, rotation_exp(Eigen::Vector3d(0.4, 0.5, 0.1)));
  r.render(truth, observed);
  for (size_t k = 0; k < pixels; ++k) {
    if (observed[k] == 0) observed[k] = 1.5f;
    if (k % 80 >= 30 && k % 80 < 36) observed[k] = 0.55f;
    if (k % 17 == 0) observed[k] = NAN;
  }
  std::vector<float> atlas(count * pixels), occlusion(count * pixels);
  // Per-pixel time: each pixel's last frame as an index into a table of frame times (dt_time_index.h).
  std::vector<uint16_t> time_index(count * pixels);
  std::vector<float> frame_times(DT_TIME_TABLE, 0.0f);
  for (size_t i = 0; i < count; ++i) {
    const Pose pose =
        model::move_about_centre(truth, Eigen::Vector3d::Zero(), Eigen::Vector3d(0.004 * i - 0.03, 0.002 * i, 0),
                                 Eigen::Vector3d(0, 0.02 * i, 0));
    r.render(pose, std::span<float>(atlas.data() + i * pixels, pixels));
  }
  for (auto& p : occlusion) p = unit(rng);
  for (unsigned f = 0; f < 64; ++f) frame_times[f] = 0.5f * unit(rng);
  for (auto& t : time_index) t = static_cast<uint16_t>(std::min(63.0f, 64 * unit(rng)));
  // The last frame's resampling, folded into weigh: particle i's state is row parents[i] (with repeats,
  // as resampling makes, and some particles nobody's parent).
  std::vector<unsigned> parents(count);
  for (size_t i = 0; i < count; ++i) parents[i] = static_cast<unsigned>((i * 5 + 3) % count / 2);
  const double now = 0.7, dt = 0.04;
  const unsigned now_index = 64;
  // The tiles also go into a paged layout like the GL atlas's: 3 tiles per row, 6 per page, 3 pages
  // (placed here by hand: page p at p * 6 tiles, tile t of it at column t % 3, row t / 3).
  const size_t width = 80, height = 60, page_width = 3 * width;
  std::vector<float> paged(2 * 6 * pixels + 2 * height * page_width, -1.0f);
  for (size_t i = 0; i < count; ++i)
    for (size_t v = 0; v < height; ++v)
      for (size_t u = 0; u < width; ++u) {
        const size_t page = i / 6, t = i % 6;
        paged[page * 6 * pixels + ((t / 3) * height + v) * page_width + (t % 3) * width + u] =
            atlas[i * pixels + v * width + u];
      }
  using Layout = dt_atlas_layout;
  const std::pair<std::vector<float>*, Layout> layouts[] = {{&atlas, {80, 60, 1, static_cast<dt_u32>(count)}},
                                                            {&paged, {80, 60, 3, 6}}};
  // The state window (dt_window.h): the whole image, or rows of 16x12 pixels that were at (31, 24) and
  // are at (34, 26) this frame: a pixel outside this frame's window keeps no state, one new to it
  // starts fresh (0.1 at time 0), and both still add their terms.
  const float fresh = 0.1f;
  const dt_window whole{0, 0, 0, 0, 80, 60, 80, 60, 80, fresh}, moved{34, 26, 31, 24, 16, 12, 16, 12, 80, fresh};
  for (int run = 0; run < 9; ++run) {
    const int mode = run % 3;
    const auto& [laid_out, layout] = layouts[run < 6 ? run / 3 : 0];
    const dt_window win = run < 6 ? whole : moved;
    const size_t row = static_cast<size_t>(win.width) * win.height;
    INFO("atlas with " << layout.tiles_per_row << " tiles per row, state window " << win.width << "x" << win.height);
    auto program = build(*q, "weigh.cl", mode);
    auto kernel = program->kernel("weigh");
    compute::Buffer<float> a(*q, laid_out->size()), o(*q, pixels), occ(*q, count * row), occ_to(*q, count * row),
        table(*q, DT_TIME_TABLE), ll(*q, count), lw(*q, count);
    compute::Buffer<uint16_t> tim(*q, count * row), tim_to(*q, count * row);
    compute::Buffer<unsigned> parent_buffer(*q, count), no_boxes(*q, 4);  // whole tiles
    a.upload(*laid_out);
    o.upload(observed);
    occ.upload(std::vector<float>(occlusion.begin(), occlusion.begin() + static_cast<std::ptrdiff_t>(count * row)));
    tim.upload(
        std::vector<uint16_t>(time_index.begin(), time_index.begin() + static_cast<std::ptrdiff_t>(count * row)));
    // Written where the mode keeps state: the off mode must leave these as they are.
    occ_to.upload(std::vector<float>(count * row, -1.0f));
    tim_to.upload(std::vector<uint16_t>(count * row, 7));
    parent_buffer.upload(parents);
    table.upload(frame_times);
    lw.upload(std::vector<float>(count, 1.0f));
    q->launch(*kernel, compute::NdRange::linear(count * kGroup, kGroup), a, o, parent_buffer, occ, tim, occ_to, tim_to,
              table, ll, lw, static_cast<unsigned>(pixels), model_args(), static_cast<float>(now), now_index,
              static_cast<float>(dt), layout, win, no_boxes, 0u, 0u)
        ->wait();
    const auto got_ll = ll.download(), got_lw = lw.download(), got_occ = occ_to.download();
    const auto got_index = tim_to.download();
    const auto got_table = table.download();
    // Per-pixel time writes this frame's time into the table; the other modes leave it.
    CHECK(got_table[now_index] == (mode == 0 ? static_cast<float>(now) : 0.0f));
    const OcclusionModel chain;
    size_t outside = 0, fresh_inside = 0;  // used pixels outside the window, and new to it
    for (size_t i = 0; i < count; ++i) {
      double expected = 0;
      for (size_t k = 0; k < pixels; ++k) {
        // Particle i's rendering, where its state goes in its own row (if its window holds the pixel),
        // and its parent's state (if the pixel was in the window before and still is; else fresh).
        const size_t u = k % width, v = k / width;
        const bool kept = u >= win.u0 && u < win.u0 + win.width && v >= win.v0 && v < win.v0 + win.height;
        const bool before =
            kept && u >= win.last_u0 && u < win.last_u0 + win.width && v >= win.last_v0 && v < win.last_v0 + win.height;
        const size_t at = i * row + (v - win.v0) * win.width + (u - win.u0);
        const size_t from = parents[i] * row + (v - win.last_v0) * win.width + (u - win.last_u0);
        const double kept_p = before ? occlusion[from] : fresh;
        const unsigned seen = before ? time_index[from] : DT_TIME_NEVER;
        double p = mode == 1 ? (before ? model::propagate_occlusion(chain, kept_p, dt)
                                       : model::propagate_occlusion(chain, fresh, now))
                             : kept_p;
        const double y = observed[k], y_hat = atlas[i * pixels + k];
        const bool used = y_hat > 0 && DepthImage::is_valid(static_cast<float>(y));
        if (used && mode == 0) p = model::propagate_occlusion(chain, kept_p, now - frame_times[seen]);
        if (mode == 2) p = 0;
        double updated = mode == 2 ? -1.0 : p;
        if (used) {
          const auto d = reference::pixel_densities(ObservationModel{}, y, y_hat);
          expected += reference::pixel_log_ratio(d, p);
          if (mode != 2) updated = reference::occlusion_posterior(d, p);
        }
        outside += used && !kept;
        fresh_inside += used && kept && !before;
        if (!kept) continue;
        REQUIRE(got_index[at] == (mode == 0 ? (used ? now_index : seen) : 7));
        // Every pixel's state written: the parent's carried over where the particle's update left it.
        REQUIRE(got_occ[at] == Approx(updated).epsilon(1e-4).margin(1e-6));
      }
      INFO("mode " << mode << " particle " << i);
      REQUIRE(got_ll[i] == Approx(expected).epsilon(1e-4).margin(1e-3));
      REQUIRE(got_lw[i] == Approx(expected + 1.0).epsilon(1e-4).margin(1e-3));
    }
    if (run >= 6) {  // the moved window cuts the object and takes in pixels it did not hold
      CHECK(outside > 20);
      CHECK(fresh_inside > 20);
    }
  }
}

TEST_CASE("weigh kernel stays finite and equal to the reference for observations far beyond the sensor's range",
          "[device][kernels][robustness]") {
  // The densities' exp overflows in float beyond ~150 m (in double ~250 m): both scale it away.
  if (!test::device_available()) return;
  auto q = compute::open_device(test::device_selector());
  const std::vector<float> observed = {0.5f, 1.0f, 40.0f, 160.0f, 300.0f, 1000.0f, 1e4f, 3e5f};
  const std::vector<float> atlas = {0.5f, 0.9f, 1.0f, 1.0f, 6.0f, 2.0f, 1.0f, 0.3f};
  const size_t pixels = observed.size();
  auto program = build(*q, "weigh.cl", 0);
  auto kernel = program->kernel("weigh");
  const std::vector<float> occlusion(pixels, 0.3f);
  compute::Buffer<float> a(*q, pixels), o(*q, pixels), occ(*q, pixels), occ_to(*q, pixels), table(*q, DT_TIME_TABLE),
      ll(*q, 1), lw(*q, 1);
  compute::Buffer<uint16_t> tim(*q, pixels), tim_to(*q, pixels);
  compute::Buffer<unsigned> parents(*q, 1), no_boxes(*q, 4);  // whole tiles
  parents.upload(std::vector<unsigned>{0});
  a.upload(atlas);
  o.upload(observed);
  occ.upload(occlusion);
  tim.upload(std::vector<uint16_t>(pixels, DT_TIME_NEVER));  // time 0, as now: no ageing
  table.upload(std::vector<float>(DT_TIME_TABLE, 0.0f));
  lw.upload(std::vector<float>(1, 0.0f));
  q->launch(*kernel, compute::NdRange::linear(kGroup, kGroup), a, o, parents, occ, tim, occ_to, tim_to, table, ll, lw,
            static_cast<unsigned>(pixels), model_args(), 0.0f, 0u, 0.0f,
            dt_atlas_layout{static_cast<dt_u32>(pixels), 1, 1, 1},
            dt_window{0, 0, 0, 0, static_cast<dt_u32>(pixels), 1, static_cast<dt_u32>(pixels), 1,
                      static_cast<dt_u32>(pixels), 0.1f},
            no_boxes, 0u, 0u)
      ->wait();
  double expected = 0;
  for (size_t k = 0; k < pixels; ++k) {
    const auto d = reference::pixel_densities(ObservationModel{}, observed[k], atlas[k]);
    const double term = reference::pixel_log_ratio(d, 0.3);
    INFO("y " << observed[k] << " y_hat " << atlas[k]);
    REQUIRE(std::isfinite(term));
    REQUIRE(std::isfinite(reference::occlusion_posterior(d, 0.3)));
    expected += term;
  }
  const auto got_occ = occ_to.download();
  for (size_t k = 0; k < pixels; ++k) {
    INFO("pixel " << k);
    REQUIRE(std::isfinite(got_occ[k]));
    CHECK(got_occ[k] == Approx(reference::occlusion_posterior(
                                   reference::pixel_densities(ObservationModel{}, observed[k], atlas[k]), 0.3))
                            .epsilon(1e-4)
                            .margin(1e-6));
  }
  CHECK(ll.download()[0] == Approx(expected).epsilon(1e-4).margin(1e-3));
}

TEST_CASE("summarize kernel equals the reference normalization and mean pose", "[device][kernels]") {
  if (!test::device_available()) return;
  auto q = compute::open_device(test::device_selector());
  compute::ProgramCache programs(*q);
  // 1,000 particles: more than one pass of summarize.cl's one group; 40,000: summarize_wide.cl's passes
  // over many groups, as the filter runs them for large clouds.
  const size_t count = GENERATE(size_t{1000}, size_t{40000});
  // The rotation mean's Karcher steps: all of them, or none where the refinement replaces the mean
  // (the rotation then stays the heaviest particle's).
  const unsigned karcher_steps = GENERATE(unsigned{DT_KARCHER_STEPS}, 0u);
  const bool wide = count >= kWideSummaryParticles;
  INFO(count << " particles, " << (wide ? "many groups" : "one group") << ", " << karcher_steps << " Karcher steps");
  std::mt19937 rng(11);
  std::normal_distribution<double> n;
  std::vector<model::ParticleState> states(count);
  std::vector<double> log_weights(count), log_likelihoods(count);
  const model::ParticleState base = random_state(rng);
  for (size_t i = 0; i < count; ++i) {
    states[i] = base;
    states[i].pose = model::move_about_centre(base.pose, Eigen::Vector3d(0, 0, 0.02),
                                              Eigen::Vector3d(0.01 * n(rng), 0.01 * n(rng), 0.01 * n(rng)),
                                              Eigen::Vector3d(0.1 * n(rng), 0.1 * n(rng), 0.1 * n(rng)));
    states[i].linear_velocity = Eigen::Vector3d(n(rng), n(rng), n(rng));
    log_weights[i] = -500 + 3 * n(rng);     // far from 0: the kernel must subtract the maximum
    if (i % 7 == 3) log_weights[i] -= 300;  // weights 0 in float, whose states are not read
    log_likelihoods[i] = 10 * n(rng);
  }
  compute::Buffer<float> state(*q, count * DT_STATE_STRIDE), lw(*q, count), ll(*q, count), w(*q, count),
      est(*q, DT_EST_SIZE);
  state.upload(pack_particles(states));
  lw.upload(std::vector<float>(log_weights.begin(), log_weights.end()));
  ll.upload(std::vector<float>(log_likelihoods.begin(), log_likelihoods.end()));
  const float kl_threshold = 2.0f;
  if (wide) {
    // Made for a larger cloud, as a filter's whose count has changed: it runs count's groups.
    WideSummary summary(*q, programs, "DT_OCCLUSION=0", 3 * count);
    CHECK(summary.groups(count) > 1);
    CHECK(summary.groups(count) < summary.groups(3 * count));
    summary.summarize(count, state, lw, ll, w, est, 0.0f, 0.0f, 0.02f, kl_threshold, karcher_steps);
    q->finish();
  } else {
    auto summarize = build(*q, "summarize.cl")->kernel("summarize");
    q->launch(*summarize, compute::NdRange::linear(kGroup, kGroup), state, lw, ll, w, est, static_cast<unsigned>(count),
              0.0f, 0.0f, 0.02f, kl_threshold, karcher_steps)
        ->wait();
  }
  const auto e = est.download();
  const auto summary = reference::summarize_log_weights(log_weights);
  std::vector<Pose> poses;
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < count; ++i) {
    poses.push_back(states[i].pose);
    velocity += summary.normalized[i] * states[i].linear_velocity;
  }
  Pose mean = reference::weighted_mean_pose(poses, summary.normalized, Eigen::Vector3d(0, 0, 0.02));
  if (karcher_steps == 0) {  // the weighted centre, turned as the heaviest particle is
    const size_t heaviest =
        static_cast<size_t>(std::max_element(log_weights.begin(), log_weights.end()) - log_weights.begin());
    const Eigen::Vector3d centre(0, 0, 0.02), mean_centre = mean.apply(centre);
    mean.rotation = states[heaviest].pose.rotation;
    mean.translation = mean_centre - mean.rotation * centre;
  }
  const Pose got({e[DT_EST_TX], e[DT_EST_TX + 1], e[DT_EST_TX + 2]},
                 Eigen::Quaterniond(e[DT_EST_QW], e[DT_EST_QW + 1], e[DT_EST_QW + 2], e[DT_EST_QW + 3]));
  CHECK(e[DT_EST_ESS] == Approx(summary.effective_sample_size).epsilon(1e-4));
  CHECK(e[DT_EST_KL] == Approx(summary.kl_from_uniform).epsilon(1e-4));
  CHECK(e[DT_EST_RESAMPLE] == (e[DT_EST_KL] > kl_threshold ? 1.0f : 0.0f));  // the decision resample.cl reads
  CHECK(translation_error(got, mean) < 1e-6);
  CHECK(rotation_error(got, mean) < 1e-5);
  CHECK(e[DT_EST_VX] == Approx(velocity.x()).epsilon(1e-4).margin(1e-6));
  const auto weights = w.download();
  for (size_t i = 0; i < count; ++i) REQUIRE(weights[i] == Approx(summary.normalized[i]).epsilon(1e-4).margin(1e-9));
}

TEST_CASE("prefix-sum and resampling kernels choose the parents the reference does", "[device][kernels]") {
  if (!test::device_available()) return;
  auto q = compute::open_device(test::device_selector());
  auto program = build(*q, "resample.cl");
  auto prefix = program->kernel("prefix_sum");
  auto resample = program->kernel("resample_particles");
  auto scanning = program->kernel("resample_scanning");
  compute::ProgramCache programs(*q);
  std::mt19937 rng(2);
  std::exponential_distribution<double> e;
  // The last: over many groups (prefix_sum_totals, prefix_sum_ranges), as the filter for large clouds.
  // Each count with weights spread over the cloud, and with all weight on two particles and exact zeros
  // elsewhere (an effective sample size near 1: flat runs of cumulative weights, ties everywhere).
  for (size_t count : {size_t{1}, size_t{5}, size_t{200}, size_t{2000}, size_t{5000}, size_t{40000}})
    for (const bool degenerate : {false, true}) {
      const bool wide = count >= kWideSummaryParticles;
      INFO(count << " particles, " << (wide ? "many groups" : "one group") << (degenerate ? ", two heavy" : ""));
      std::vector<double> w(count);
      double sum = 0;
      for (auto& x : w) sum += x = e(rng) * (e(rng) > 1.5 ? 20 : 1);  // a few heavy particles
      if (degenerate) {
        std::fill(w.begin(), w.end(), 0.0);
        w[count / 3] = 0.7;
        w[count - 1] += 0.3;
        sum = 1.0;
      }
      for (auto& x : w) x /= sum;
      compute::Buffer<float> weights(*q, count), cumulative(*q, 2 * count), from(*q, count * DT_STATE_STRIDE),
          to(*q, count * DT_STATE_STRIDE), log_weights(*q, count), no_correction(*q, 6);
      compute::Buffer<unsigned> parents(*q, count);
      compute::Buffer<float> decision(*q, DT_EST_SIZE);  // the estimate buffer, saying "resample"
      std::vector<float> resample_flag(DT_EST_SIZE, 0.0f);
      resample_flag[DT_EST_RESAMPLE] = 1.0f;
      decision.upload(resample_flag);
      // The reference gets the very floats the device sees, so only the arithmetic differs.
      const std::vector<float> w_float(w.begin(), w.end());
      weights.upload(w_float);
      w.assign(w_float.begin(), w_float.end());
      if (wide) {
        WideSummary summary(*q, programs, "DT_OCCLUSION=0", 3 * count);  // a larger cloud's, as above
        CHECK(summary.groups(count) > 1);
        summary.prefix_sum(count, weights, cumulative, decision);
      } else {
        q->launch(*prefix, compute::NdRange::linear(kGroup, kGroup), weights, cumulative, static_cast<unsigned>(count),
                  decision);
      }
      const float u = dt_uniform01(dt_random_words(4, 0, 1, DT_STREAM_RESAMPLE, 0).v[0]);
      q->launch(*resample, compute::NdRange::linear((count + 63) / 64 * 64, 64), cumulative, parents,
                static_cast<unsigned>(count), u, decision, from, to, log_weights, no_correction, 0.0f, 0.0f, 0.0f, 0u)
          ->wait();
      const auto got = parents.download();
      const auto expected = reference::systematic_resample(w, u);
      const auto cum = cumulative.download();
      CHECK(cum[2 * count - 2] + cum[2 * count - 1] == Approx(1.0).epsilon(1e-5));
      for (size_t j = 0; j < count; ++j) REQUIRE(static_cast<int>(got[j]) == expected[j]);
      if (wide) continue;
      // Every group scanning the weights itself (the filter's kernel for small clouds): the same parents.
      parents.upload(std::vector<unsigned>(count, 12345u));
      q->launch(*scanning, compute::NdRange::linear((count + kGroup - 1) / kGroup * kGroup, kGroup), weights, parents,
                static_cast<unsigned>(count), u, decision, from, to, log_weights, no_correction, 0.0f, 0.0f, 0.0f, 0u)
          ->wait();
      const auto scanned = parents.download();
      for (size_t j = 0; j < count; ++j) REQUIRE(static_cast<int>(scanned[j]) == expected[j]);
    }
}

TEST_CASE("resampling kernels follow the decision in the estimate buffer: gather, or copy and keep",
          "[device][kernels]") {
  // The per-pixel rows are not gathered here: the next weigh reads them through parents (its test).
  if (!test::device_available()) return;
  auto q = compute::open_device(test::device_selector());
  auto program = build(*q, "resample.cl");
  const unsigned count = 3;
  std::vector<float> state(count * DT_STATE_STRIDE);
  for (size_t i = 0; i < state.size(); ++i) state[i] = static_cast<float>(i);
  // Cumulative weights (float-float pairs), or for resample_scanning the weights, that make every child
  // take particle 0 when resampling.
  const std::vector<float> cumulative_in = {1.0f, 0.0f, 1.0f, 0.0f, 1.0f, 0.0f},
                           weights_in = {1.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
  for (const char* kernel : {"resample_particles", "resample_scanning"})
    for (const bool resampling : {false, true}) {
      INFO(kernel << (resampling ? ", resampling" : ", not resampling"));
      auto resample = program->kernel(kernel);
      const bool scanning = std::string(kernel) == "resample_scanning";
      std::vector<float> flag(DT_EST_SIZE, 0.0f);
      flag[DT_EST_RESAMPLE] = resampling ? 1.0f : 0.0f;
      compute::Buffer<float> decision(*q, DT_EST_SIZE), from(*q, state.size()), to(*q, state.size()),
          weights(*q, count), cumulative(*q, cumulative_in.size()), no_correction(*q, 6);
      compute::Buffer<unsigned> parents(*q, count);
      decision.upload(flag);
      from.upload(state);
      to.upload(std::vector<float>(state.size(), -1.0f));
      weights.upload(std::vector<float>(count, 7.0f));
      cumulative.upload(scanning ? weights_in : cumulative_in);
      parents.upload(std::vector<unsigned>{2, 2, 2});  // overwritten
      q->launch(*resample, compute::NdRange::linear(kGroup, kGroup), cumulative, parents, count, 0.5f, decision, from,
                to, weights, no_correction, 0.0f, 0.0f, 0.0f, 0u);
      // Without resampling each is its own parent: the next weigh reads every particle's own row.
      const std::vector<unsigned> expected_parents =
          resampling ? std::vector<unsigned>(count, 0u) : std::vector<unsigned>{0, 1, 2};
      CHECK(parents.download() == expected_parents);
      const auto got_state = to.download(), got_weights = weights.download();
      for (unsigned child = 0; child < count; ++child) {
        for (unsigned k = 0; k < DT_STATE_STRIDE; ++k)
          REQUIRE(got_state[child * DT_STATE_STRIDE + k] == state[expected_parents[child] * DT_STATE_STRIDE + k]);
        REQUIRE(got_weights[child] == (resampling ? 0.0f : 7.0f));
      }
    }
}

// With the refinement on, every child is moved by its correction twist about the mesh's centre as it
// is gathered: the pose the reference's apply_twist gives, the velocities copied unchanged.
TEST_CASE("the resampling kernels move each child by the refinement's correction", "[device][kernels][refine]") {
  if (!test::device_available()) return;
  auto q = compute::open_device(test::device_selector());
  auto program = build(*q, "resample.cl");
  const std::vector<Pose> poses = {
      Pose({0.01, -0.02, 0.5}, Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()))),
      Pose({-0.05, 0.03, 0.7}, Eigen::Quaterniond(Eigen::AngleAxisd(-1.2, Eigen::Vector3d(0, 1, 0)))),
  };
  const unsigned count = static_cast<unsigned>(poses.size());
  std::vector<float> state(count * DT_STATE_STRIDE, 0.0f);
  for (unsigned i = 0; i < count; ++i) {
    float* s = &state[i * DT_STATE_STRIDE];
    const Eigen::Quaterniond& r = poses[i].rotation;
    for (int k = 0; k < 3; ++k) s[DT_TX + k] = static_cast<float>(poses[i].translation[k]);
    s[DT_QW] = static_cast<float>(r.w()), s[DT_QW + 1] = static_cast<float>(r.x());
    s[DT_QW + 2] = static_cast<float>(r.y()), s[DT_QW + 3] = static_cast<float>(r.z());
    for (int k = DT_VX; k < DT_STATE_STRIDE; ++k) s[k] = 0.25f * static_cast<float>(k + i);
  }
  reference::Vector6d twist;
  twist << 0.002, -0.001, 0.003, 0.01, -0.02, 0.015;
  const Eigen::Vector3d centre(0.01, 0.02, -0.03);
  const std::vector<float> twist_f(twist.data(), twist.data() + 6);
  std::vector<float> flag(DT_EST_SIZE, 0.0f);  // not resampling: each child is its own parent
  compute::Buffer<float> decision(*q, DT_EST_SIZE), from(*q, state.size()), to(*q, state.size()), weights(*q, count),
      cumulative(*q, 2 * count), correction(*q, 6);
  compute::Buffer<unsigned> parents(*q, count);
  decision.upload(flag);
  from.upload(state);
  correction.upload(twist_f);
  cumulative.upload(std::vector<float>(2 * count, 0.5f));  // resample_scanning reads weights here
  for (const char* kernel : {"resample_particles", "resample_scanning"}) {
    INFO(kernel);
    to.upload(std::vector<float>(state.size(), -1.0f));
    q->launch(*program->kernel(kernel), compute::NdRange::linear(kGroup, kGroup), cumulative, parents, count, 0.5f,
              decision, from, to, weights, correction, static_cast<float>(centre.x()), static_cast<float>(centre.y()),
              static_cast<float>(centre.z()), 1u);
    const auto got = to.download();
    for (unsigned i = 0; i < count; ++i) {
      const float* s = &got[i * DT_STATE_STRIDE];
      const Pose moved({s[DT_TX], s[DT_TX + 1], s[DT_TX + 2]},
                       Eigen::Quaterniond(s[DT_QW], s[DT_QW + 1], s[DT_QW + 2], s[DT_QW + 3]));
      const Pose expected = reference::apply_twist(poses[i], centre, twist);
      CHECK(translation_error(moved, expected) < 1e-6);
      CHECK(rotation_error(moved, expected) < 1e-5);
      CHECK(translation_error(moved, poses[i]) > 1e-3);  // it did move
      for (int k = DT_VX; k < DT_STATE_STRIDE; ++k) REQUIRE(s[k] == state[i * DT_STATE_STRIDE + k]);
    }
  }
}
