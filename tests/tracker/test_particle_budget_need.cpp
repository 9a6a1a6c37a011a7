// What a frame budget's count needs beyond the confidence: the particles a direction the fit leaves
// undetermined asks for (fit_spread_ratio against the motion model's noise), and the frame after
// initialize() from a spread, which runs what a search's budget affords.
#include <catch2/catch.hpp>
#include <cmath>
#include <depthtrack/synth.hpp>
#include <depthtrack/tracker.hpp>
#include <limits>
#include <numbers>

#include "synth_frames.hpp"
#include "tracker/particle_budget.hpp"

using namespace depthtrack;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

namespace {

// A confident frame of `particles`: 0.09 ms a particle in the loops, 3 ms besides.
Estimate confident_frame(int particles) {
  Estimate e;
  e.particles = particles;
  e.timings.render_ms = 0.09 * particles;
  e.timings.total_ms = 3 + 0.09 * particles;
  e.confidence = 0.95;
  e.status = TrackStatus::Tracking;
  return e;
}

// A fit covariance with these standard deviations: translations (metres) and rotations (radians).
Matrix6d fit_with(double t0, double t1, double t2, double r0, double r1, double r2) {
  Matrix6d c = Matrix6d::Zero();
  const double s[6] = {t0, t1, t2, r0, r1, r2};
  for (int i = 0; i < 6; ++i) c(i, i) = s[i] * s[i];
  return c;
}

}  // namespace

TEST_CASE("the fit's spread is its widest direction over a frame's motion noise", "[budget]") {
  const MotionModel motion;  // 2.5 mm and 0.02 rad a reference frame
  // Widest translation 1 mm: 0.4 of 2.5 mm; widest rotation 0.03 rad: 1.5 of 0.02. The larger: 1.5.
  CHECK(fit_spread_ratio(fit_with(1e-3, 5e-4, 2e-4, 0.01, 0.03, 0.01), motion) == Approx(1.5));
  // Translation the wider one: 5 mm is 2 of 2.5 mm.
  CHECK(fit_spread_ratio(fit_with(5e-3, 1e-4, 1e-4, 0.001, 0.001, 0.001), motion) == Approx(2.0));
  // A weak direction between the axes: 0.04 rad along (cos 30, sin 30, 0), 0.01 across. Each diagonal
  // entry alone is at most 0.04^2 cos^2 30 + 0.01^2 sin^2 30 (0.0350^2): the widest direction is 0.04.
  Matrix6d turned = fit_with(1e-4, 1e-4, 1e-4, 0, 0, 0);
  const double a = std::numbers::pi / 6;
  Eigen::Matrix3d r;
  r << std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1;
  turned.block<3, 3>(3, 3) = r * Eigen::Vector3d(0.04 * 0.04, 1e-4, 1e-4).asDiagonal() * r.transpose();
  CHECK(std::sqrt(turned(3, 3)) == Approx(0.0350).epsilon(1e-3));
  CHECK(fit_spread_ratio(turned, motion) == Approx(2.0));
  // Set apart (undetermined): +infinity; no fit (NaN): NaN.
  Matrix6d apart = fit_with(1e-4, 1e-4, 1e-4, 0.001, 0.001, 0.001);
  apart(5, 5) = std::numeric_limits<double>::infinity();
  CHECK(fit_spread_ratio(apart, motion) == std::numeric_limits<double>::infinity());
  CHECK(std::isnan(fit_spread_ratio(Matrix6d::Constant(std::nan("")), motion)));
  // The noise is the configuration's: half the angular noise, twice the ratio.
  MotionModel calmer;
  calmer.sigma_angular = 0.01;
  CHECK(fit_spread_ratio(fit_with(1e-3, 5e-4, 2e-4, 0.01, 0.03, 0.01), calmer) == Approx(3.0));
}

TEST_CASE("a confident frame keeps the particles its fit leaves to them", "[budget]") {
  // 30 ms: (30 - 3) / 0.09 = 300 afforded, so the count is the need's: 10 + need * 190.
  ParticleBudget budget(30.0, 10, 200, 0.5);
  budget.next(true);
  budget.observe(confident_frame(100), fit_with(1e-4, 1e-4, 1e-4, 0.001, 0.001, 0.001));
  CHECK(budget.afforded() == 200);
  for (int i = 0; i < ParticleBudget::kSettleFrames; ++i) {
    CHECK(budget.next(false) == 200);  // settling
    budget.observe(confident_frame(200), fit_with(1e-4, 1e-4, 1e-4, 0.001, 0.001, 0.001));
  }
  // A rotation the fit knows to 0.03 rad, 1.5 times a frame's 0.02: need (1.5 - 1) / (2 - 1) = 0.5,
  // 10 + 0.5 * 190 = 105 from the next frame on; down by at most a fifth a frame: 128, then 105.
  const Matrix6d half = fit_with(1e-4, 1e-4, 1e-4, 0.001, 0.03, 0.001);
  CHECK(budget.next(false) == 160);  // the last frame's fit left nothing: need 0, a fifth less
  budget.observe(confident_frame(160), half);
  CHECK(budget.next(false) == 128);
  budget.observe(confident_frame(128), half);
  CHECK(budget.next(false) == 105);
  budget.observe(confident_frame(105), half);
  CHECK(budget.next(false) == 105);
  // 1.3 times: need 0.3, 10 + 0.3 * 190 = 67 once the fall allows it (84, 68, then 67).
  const Matrix6d less = fit_with(1e-4, 1e-4, 1e-4, 0.001, 0.026, 0.001);
  budget.observe(confident_frame(105), less);
  CHECK(budget.next(false) == 84);
  budget.observe(confident_frame(84), less);
  CHECK(budget.next(false) == 68);
  budget.observe(confident_frame(68), less);
  CHECK(budget.next(false) == 67);
  // Twice or more (or set apart): the most the budget affords, at once.
  budget.observe(confident_frame(58), fit_with(1e-4, 1e-4, 1e-4, 0.001, 0.05, 0.001));
  CHECK(budget.next(false) == 200);
  // No fit (NaN) says nothing: the confidence's need alone (0 at 0.95), falling by a fifth a frame.
  budget.observe(confident_frame(200), Matrix6d::Constant(std::nan("")));
  CHECK(budget.next(false) == 160);
  // Within a frame's noise: 0, as without a fit.
  budget.observe(confident_frame(160), fit_with(2e-3, 1e-4, 1e-4, 0.019, 0.001, 0.001));
  CHECK(budget.next(false) == 128);
}

// A GPU's range, 10 to 100,000 particles: a fifth a frame would take 41 frames to thin a confident cloud;
// it falls by (10 / 100,000)^(1/14) = 0.518 a frame instead, crossing the range in 14 frames.
TEST_CASE("a confident cloud thins from the most to the fewest in 14 frames on any range", "[budget]") {
  // Frames of 1e-5 ms a particle (1 ms at 100,000) and 1 ms besides: everything affordable within 5 ms.
  const auto gpu_frame = [](int particles) {
    Estimate e;
    e.particles = particles;
    e.timings.render_ms = 1e-5 * particles;
    e.timings.total_ms = 1 + 1e-5 * particles;
    e.confidence = 0.95;
    e.status = TrackStatus::Tracking;
    return e;
  };
  ParticleBudget budget(5.0, 10, 100000, 0.5);
  int count = budget.next(true);
  for (int i = 0; i <= ParticleBudget::kSettleFrames; ++i) {  // the new cloud and its settling frames
    budget.observe(gpu_frame(count));
    count = budget.next(false);
  }
  const double keep = std::pow(10.0 / 100000.0, 1.0 / 14);
  CHECK(count == static_cast<int>(std::ceil(keep * 100000)));  // 51,795: the first frame of the fall
  int frames = 1;
  while (count > 10) {
    budget.observe(gpu_frame(count));
    const int next = budget.next(false);
    CHECK(next == std::max(10, static_cast<int>(std::ceil(keep * count))));
    count = next;
    ++frames;
  }
  CHECK(frames == 15);  // 14 frames' factor, each count rounded up: the 15th frame reaches 10
  // The CPU's default range, 10 to 200, keeps the fifth a frame ((10 / 200)^(1/14) = 0.807 is slower): the
  // test above falls 200 -> 160 -> 128.
}

TEST_CASE("the frame after initialize() runs what a search's budget affords", "[budget]") {
  // Primed at 1/16 ms a particle, 10 of them fixed (0.625 ms): a 5 ms frame affords (5 - 0.625) * 16 =
  // 70, a 500 ms search all 200, 3 ms 38.
  ParticleBudget budget(5.0, 10, 200, 0.5);
  budget.prime(0.0625);
  CHECK(budget.next(true) == 70);
  CHECK(budget.next_initial(500.0) == 200);
  CHECK(budget.next_initial(3.0) == 38);
  CHECK(budget.next(true) == 70);   // another new cloud first (a gap): the frame's budget
  CHECK(budget.next(false) == 70);  // settling
  // An initial frame of 200 particles, 0.09 ms each and 3 ms besides (21 ms where 13.125 were
  // predicted) moves the primed model a quarter of the way, 0.069375 ms a particle and 1.21875 fixed,
  // and keeps no miss: (5 - 1.21875) / 0.069375 = 54 afforded. A frame of the budget's own is missed.
  ParticleBudget initial(5.0, 10, 200, 0.5);
  initial.prime(0.0625);
  CHECK(initial.next_initial(500.0) == 200);
  CHECK(initial.next(false) == 200);
  initial.observe(confident_frame(200));
  CHECK(initial.per_particle_ms() == Approx(0.069375));
  CHECK(initial.fixed_ms() == Approx(1.21875));
  CHECK(initial.afforded() == 54);
  CHECK(initial.next(false) == 54);
  // 54 particles of 0.09 ms and 3 ms besides: 7.86 ms where 4.965 were predicted. The 2.895 ms overrun
  // counts as a tenth of the budget (0.5 ms, the most one frame counts while no room is kept yet):
  // 2.326 sqrt(0.1 * 0.5^2) kept free.
  initial.observe(confident_frame(54));
  const double per = 0.09, fixed = 1.21875 + 0.25 * (3 - 1.21875);  // slower a particle: set at once
  CHECK(initial.afforded() == static_cast<int>((5.0 - fixed - 2.326 * std::sqrt(0.1 * 0.25)) / per));
  // Unprimed the model has no times: the most.
  ParticleBudget unprimed(5.0, 10, 200, 0.5);
  CHECK(unprimed.next_initial(500.0) == 200);
  CHECK(unprimed.next(false) == 200);  // that frame's own choice
  // Then the new cloud settles on what the frame's budget affords: a 200-particle frame of 0.09 ms
  // each and 3 ms besides sets the unprimed model to its times, (5 - 3) / 0.09 = 22 afforded.
  unprimed.observe(confident_frame(200));
  CHECK(unprimed.next(false) == unprimed.afforded());
  CHECK(unprimed.afforded() == static_cast<int>((5.0 - 3.0) / 0.09));
}

TEST_CASE("a budgeted tracker's first frame runs the search budget's count, the next ones the frame's", "[budget]") {
  const Mesh mesh = builtin_demo_mesh();
  const SynthConfig synth = test::small_scene(3);
  const auto frames = test::synthesize(mesh, synth);
  TrackerConfig config;
  config.particles = 60;
  config.budget_ms = 0.2;           // a frame affords few particles on any machine
  config.recovery.budget_ms = 1e4;  // a search all 60
  Tracker tracker(mesh, synth.camera, config);
  tracker.initialize(frames[0].ground_truth, InitialSpread{0.01, 0.05});
  CHECK(tracker.update(frames[0].depth, frames[0].timestamp).particles == 60);
  CHECK(tracker.update(frames[1].depth, frames[1].timestamp).particles < 60);
}
