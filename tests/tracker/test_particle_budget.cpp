// The frame budget (TrackerConfig::budget_ms): the count it chooses from measured times and the
// estimate's state, the host filter's change of particle count, and a budgeted run replayed on the
// sequential reference with the same counts, estimate for estimate.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <depthtrack/error.hpp>
#include <depthtrack/synth.hpp>
#include <depthtrack/tracker.hpp>
#include <random>
#include <set>
#include <vector>

#include "reference/reference_filter.hpp"
#include "reference/weights.hpp"
#include "synth_frames.hpp"
#include "tracker/particle_budget.hpp"

using namespace depthtrack;
using Catch::Matchers::Contains;

namespace {

// A frame of `particles` whose particle loops took loops_ms (split over the four steps) of total_ms.
Estimate timed_frame(int particles, double loops_ms, double total_ms, double confidence,
                     TrackStatus status = TrackStatus::Tracking) {
  Estimate e;
  e.particles = particles;
  e.timings.propagate_ms = 0.1 * loops_ms;
  e.timings.render_ms = 0.4 * loops_ms;
  e.timings.weigh_ms = 0.4 * loops_ms;
  e.timings.resample_ms = 0.1 * loops_ms;
  e.timings.total_ms = total_ms;
  e.confidence = confidence;
  e.status = status;
  return e;
}

}  // namespace

TEST_CASE("a particle budget affords what its measured times allow and follows the confidence", "[budget]") {
  ParticleBudget budget(10.0, 10, 200, 0.5);
  // Untimed, the first frame (a new cloud) runs the fewest; its time sizes the next.
  CHECK(budget.next(true) == 10);
  // 100 particles: loops 9 ms (0.09 ms each), 3 ms besides: (10 - 3) / 0.09 = 77.8 afforded.
  budget.observe(timed_frame(100, 9.0, 12.0, 0.95));
  CHECK(budget.per_particle_ms() == Approx(0.09));
  CHECK(budget.fixed_ms() == Approx(3.0));
  CHECK(budget.afforded() == 77);
  // The new cloud settles for kSettleFrames more frames on what the budget affords, though confident.
  for (int i = 0; i < ParticleBudget::kSettleFrames; ++i) {
    CHECK(budget.next(false) == 77);
    budget.observe(timed_frame(77, 77 * 0.09, 3 + 77 * 0.09, 0.95));
  }
  CHECK(budget.afforded() == 77);
  // Confident: down by at most a fifth a frame (ceil 0.8 * 77 = 62, then 50, 40, ...) to the fewest.
  CHECK(budget.next(false) == 62);
  CHECK(budget.next(false) == 50);
  CHECK(budget.next(false) == 40);
  for (int i = 0; i < 20; ++i) budget.next(false);
  CHECK(budget.next(false) == 10);
  // The same time again: the model's miss is 0, the afforded count stays.
  budget.observe(timed_frame(10, 0.9, 3.9, 0.7));
  CHECK(budget.afforded() == 77);
  // Confidence 0.7, halfway from kConfident (0.9) to lost (0.5): 10 + 0.5 * 190 = 105 wanted, 77 afforded.
  CHECK(budget.next(false) == 77);
  // Lost: the most the budget affords; and when frames get slower, fewer.
  budget.observe(timed_frame(77, 77 * 0.09, 3 + 77 * 0.09, 0.2, TrackStatus::Lost));
  CHECK(budget.next(false) == 77);
  budget.observe(timed_frame(77, 77 * 0.2, 3 + 77 * 0.2, 0.2, TrackStatus::Lost));
  // Slower a particle than the model, the frame sets it at once: 0.2. It overran the model by 77 * 0.11 =
  // 8.47 ms, counted as a tenth of the budget (1 ms, the most one frame counts while the overruns' root
  // mean square is 0): their mean square 0.1 * 1^2, and 2.326 sqrt(0.1) = 0.736 ms kept free.
  CHECK(budget.per_particle_ms() == Approx(0.2));
  CHECK(budget.overrun_room_ms() == Approx(2.326 * std::sqrt(0.1)));
  CHECK(budget.afforded() == static_cast<int>((10.0 - 3.0 - 2.326 * std::sqrt(0.1)) / 0.2));
  // A faster frame moves it a quarter of the way: 0.2 + 0.25 (0.1 - 0.2) = 0.175.
  budget.observe(timed_frame(30, 30 * 0.1, 3 + 30 * 0.1, 0.2, TrackStatus::Lost));
  CHECK(budget.per_particle_ms() == Approx(0.175));
  CHECK(budget.next(false) == budget.afforded());
  // A search takes its own budget: it does not count as the frame's fixed time.
  Estimate searched = timed_frame(77, 77 * 0.175, 3 + 77 * 0.175 + 400, 0.95);
  searched.timings.search_ms = 400;
  const double fixed_before = budget.fixed_ms();
  budget.observe(searched);
  CHECK(budget.fixed_ms() == Approx(fixed_before + 0.25 * (3.0 - fixed_before)));
  // A budget below the fixed time runs the fewest.
  ParticleBudget tight(2.0, 10, 200, 0.5);
  tight.next(true);
  tight.observe(timed_frame(10, 1.0, 4.0, 0.95));
  CHECK(tight.afforded() == 0);
  CHECK(tight.next(true) == 10);
  CHECK_THROWS_AS(ParticleBudget(0.0, 10, 200, 0.5), InputError);
  CHECK_THROWS_AS(ParticleBudget(5.0, 20, 10, 0.5), InputError);
}

TEST_CASE("a primed particle budget sizes the first frame from one particle's time", "[budget]") {
  ParticleBudget budget(10.0, 10, 200, 0.5);
  budget.prime(std::nan(""));  // ignored: unprimed, the first frame still runs the fewest
  budget.prime(-1.0);
  CHECK(budget.fixed_ms() == 0);
  // 0.05 ms a particle, 10 of them fixed (0.5 ms): (10 - 0.5) / 0.05 = 190 for the first frame.
  budget.prime(0.05);
  CHECK(!budget.timed());
  CHECK(budget.per_particle_ms() == Approx(0.05));
  CHECK(budget.fixed_ms() == Approx(0.5));
  CHECK(budget.next(true) == 190);
  // A slow first frame (0.09 ms a particle, 3 ms fixed, 20.1 ms in all where 10 were predicted) moves the
  // model a quarter: 0.06 ms a particle, 1.125 fixed. It touched its memory first: its overrun keeps no room.
  budget.observe(timed_frame(190, 190 * 0.09, 3 + 190 * 0.09, 0.95));
  CHECK(budget.timed());
  CHECK(budget.per_particle_ms() == Approx(0.06));
  CHECK(budget.fixed_ms() == Approx(1.125));
  CHECK(budget.overrun_room_ms() == 0);
  CHECK(budget.afforded() == static_cast<int>((10.0 - 1.125) / 0.06));
  budget.prime(1.0);  // ignored once a frame is timed
  CHECK(budget.per_particle_ms() == Approx(0.06));
  // The next frame's overrun does: 190 particles at 0.07 ms where 0.06 was the model, 1.9 ms over, counted
  // as the 1 ms a frame counts at most while no room is kept yet.
  budget.observe(timed_frame(190, 190 * 0.07, 1.125 + 190 * 0.07, 0.95));
  CHECK(budget.overrun_room_ms() == Approx(2.326 * std::sqrt(0.1)));
  // Unprimed, a first frame's times replace the model (the test above): a fresh budget's first count is min.
  ParticleBudget unprimed(10.0, 10, 200, 0.5);
  CHECK(unprimed.next(true) == 10);
}

// A frame whose fit ran k of its at most K steps, each step_ms: its particle loops and fixed time as in
// timed_frame, the fit's time on top of them.
Estimate fitted_frame(int particles, double loops_ms, double fixed_ms, int steps, double step_ms) {
  Estimate e = timed_frame(particles, loops_ms, fixed_ms + loops_ms + steps * step_ms, 0.95);
  e.refine_iterations = steps;
  e.timings.refine_ms = steps * step_ms;
  return e;
}

// The fit converges after a varying number of steps, which a frame cannot know before it runs: the budget
// keeps room for all of them, so a frame whose fit runs long still ends within it.
TEST_CASE("a particle budget keeps room for the fit's most steps", "[budget]") {
  // 8 steps at most, 0.25 ms each; loops 0.0625 ms a particle; 1 ms besides.
  ParticleBudget budget(10.0, 10, 500, 0.5, MotionModel{}, 8);
  budget.next(true);
  budget.observe(fitted_frame(100, 6.25, 1.0, 3, 0.25));  // a short fit: 3 steps
  CHECK(budget.fit_step_ms() == Approx(0.25));
  CHECK(budget.fixed_ms() == Approx(1.0));  // the fit's time is not fixed time
  // (10 - 1 - 8 * 0.25) / 0.0625 = 112, not the (10 - 1.75) / 0.0625 = 132 the short fit alone would leave
  // (111 where the loops' split into the four steps rounds the time a particle up).
  const auto near_112 = [](int n) { return n == 111 || n == 112; };
  CHECK(near_112(budget.afforded()));
  // A frame of 112 particles whose fit takes every step ends at the budget: 1 + 7 + 2 ms.
  budget.observe(fitted_frame(112, 112 * 0.0625, 1.0, 8, 0.25));
  // The model predicted this frame from the fit's own steps: no overrun, the same count afforded.
  CHECK(budget.overrun_room_ms() == Approx(0).margin(1e-6));
  CHECK(near_112(budget.afforded()));
  // A step grown to 0.45 ms moves the reserve by a quarter: 0.3 ms a step.
  budget.observe(fitted_frame(112, 112 * 0.0625, 1.0, 4, 0.45));
  CHECK(budget.fit_step_ms() == Approx(0.3));
  // Without the fit's most steps (0) nothing is kept for it beyond the frames' fixed time.
  ParticleBudget unreserved(10.0, 10, 500, 0.5);
  unreserved.next(true);
  unreserved.observe(fitted_frame(100, 6.25, 1.0, 3, 0.25));
  CHECK(unreserved.fixed_ms() == Approx(1.75));
  CHECK((unreserved.afforded() == 131 || unreserved.afforded() == 132));
  CHECK_THROWS_AS(ParticleBudget(5.0, 10, 200, 0.5, MotionModel{}, -1), InputError);
}

// A CPU's frames vary about the model (here each particle's time by 3 %, normally): the room kept for
// the overruns leaves about 95 % of the frames within the budget, and costs only a few particles.
TEST_CASE("a particle budget keeps about 95 % of noisy frames within it", "[budget]") {
  const double per = 0.04, fixed = 0.5, budget_ms = 5.0;  // ms
  const double noise_free = (budget_ms - fixed) / per;    // 112.5 particles
  ParticleBudget budget(budget_ms, 10, 1000, 0.5);
  std::mt19937 random(7);
  std::normal_distribution<double> spread(1.0, 0.03);
  int count = budget.next(true), over = 0, frames = 0;
  double counted = 0;
  for (int frame = 0; frame < 600; ++frame) {
    const double loops = per * spread(random) * count;
    if (frame >= 50) {  // after the model has settled
      ++frames;
      over += fixed + loops > budget_ms;
      counted += count;
    }
    budget.observe(timed_frame(count, loops, fixed + loops, 0.2, TrackStatus::Lost));  // lost: the most afforded
    count = budget.next(false);
  }
  const double share_over = static_cast<double>(over) / frames;
  INFO(over << " of " << frames << " frames over, " << counted / frames << " particles on average");
  CHECK(share_over <= 0.08);
  CHECK(counted / frames >= 0.9 * noise_free);
  CHECK(counted / frames < noise_free);
}

// A GPU's frame is nearly flat in the count at small counts: its particle loops take a launch time a of
// their own besides b per particle, which the model's per-particle time (loops / n) overstates at small n.
// Each frame's count is then what the last one's times afford, and n -> room / (a / n + b) climbs to the
// fixed point a + b n = budget - fixed, the count the budget truly affords, from below: no frame over it.
TEST_CASE("with a GPU's times, flat at small counts, a budget climbs to what it affords and stays within it",
          "[budget]") {
  const double launches = 0.2, per = 1e-4, fixed = 1.0, budget_ms = 5.0;                         // ms
  const int most = 100000, affordable = static_cast<int>((budget_ms - fixed - launches) / per);  // 38,000
  // Primed by a device's batch of 4,096 poses scored in 0.5 ms (twice 0.5 / 4,096 a particle).
  ParticleBudget budget(budget_ms, 10, most, 0.5);
  budget.prime(2 * 0.5 / 4096);
  int count = budget.next(true);
  CHECK(count > 1000);  // the batch's prime starts far above the fewest
  for (int frame = 0; frame < 60; ++frame) {
    const double loops = launches + per * count;
    INFO("frame " << frame << ", " << count << " particles");
    REQUIRE(fixed + loops <= budget_ms + 1e-9);
    budget.observe(timed_frame(count, loops, fixed + loops, 0.2, TrackStatus::Lost));  // lost: the most afforded
    const int next = budget.next(false);
    CHECK(next >= count);  // from below, never back
    count = next;
  }
  CHECK(count == Approx(affordable).epsilon(0.01));
  CHECK(count < most);
}

TEST_CASE("the reference filter changes its particle count by resampling its weighted cloud", "[budget][filter]") {
  const Mesh mesh = builtin_demo_mesh();
  const SynthConfig synth = test::small_scene(3);
  const auto frames = test::synthesize(mesh, synth);
  TrackerConfig config;
  config.particles = 40;
  reference::ReferenceFilter filter(mesh, synth.camera, config);
  filter.initialize(frames[0].ground_truth, InitialSpread{0.01, 0.05});
  filter.update(frames[0].depth, 0.0);
  const auto before = filter.particles();
  const std::vector<double> weights = reference::summarize_log_weights(filter.log_weights()).normalized;
  filter.set_particle_count(40);  // the same count: nothing changes
  CHECK(filter.particles().size() == 40);
  CHECK(filter.particles()[7].pose.translation == before[7].pose.translation);
  filter.set_particle_count(13);
  REQUIRE(filter.particles().size() == 13);
  CHECK(filter.log_weights() == std::vector<double>(13, 0.0));
  CHECK(filter.occlusion_state().size() == 13 * filter.state_window().pixels());
  // Every child is a particle of the cloud before, and the heaviest one is among them.
  const size_t heaviest = static_cast<size_t>(std::max_element(weights.begin(), weights.end()) - weights.begin());
  bool heaviest_kept = false;
  for (const auto& child : filter.particles()) {
    const auto parent = std::find_if(before.begin(), before.end(), [&](const auto& p) {
      return p.pose.translation == child.pose.translation && p.pose.rotation.coeffs() == child.pose.rotation.coeffs();
    });
    CHECK(parent != before.end());
    heaviest_kept = heaviest_kept || static_cast<size_t>(parent - before.begin()) == heaviest;
  }
  CHECK(heaviest_kept);
  filter.update(frames[1].depth, frames[1].timestamp - frames[0].timestamp);
  CHECK(filter.last_log_likelihoods().size() == 13);
  filter.set_particle_count(40);  // back up to the most
  CHECK(filter.particles().size() == 40);
  filter.update(frames[2].depth, frames[2].timestamp - frames[1].timestamp);
  CHECK(filter.last_log_likelihoods().size() == 40);
  for (const int bad : {0, -1, 41}) {
    INFO(bad);
    CHECK_THROWS_WITH(filter.set_particle_count(bad), Contains("particle count") && Contains("[1, particles = 40]"));
  }
}

TEST_CASE("a budgeted cpu run equals the sequential reference replaying its particle counts", "[budget][cpu]") {
  const Mesh mesh = builtin_demo_mesh();
  const SynthConfig synth = test::small_scene(14);
  const auto frames = test::synthesize(mesh, synth);
  TrackerConfig config;
  config.particles = 48;
  config.min_particles = 6;
  config.seed = 3;
  // Ample: the counts follow the estimate (the most while settling, fewer as it stays confident),
  // whatever this machine's speed.
  config.budget_ms = 1e4;
  config.backend = "cpu:2";
  Tracker budgeted(mesh, synth.camera, config);
  budgeted.initialize(frames[0].ground_truth);
  std::vector<Estimate> chosen;
  for (const SynthFrame& f : frames) chosen.push_back(budgeted.update(f.depth, f.timestamp));
  std::set<int> counts;
  for (const Estimate& e : chosen) counts.insert(e.particles);
  // Primed before the first frame (ParticleBudget::prime), the ample budget affords the most at once.
  CHECK(chosen.front().particles == 48);
  CHECK(chosen[1].particles == 48);
  CHECK(counts.size() >= 3);  // the replay below is of a varying count
  CHECK_THROWS_WITH(budgeted.set_particle_count(10), Contains("budget"));

  config.budget_ms = 0;
  config.backend = "reference";
  Tracker replay(mesh, synth.camera, config);
  CHECK(replay.drawn_triangles() == budgeted.drawn_triangles());  // 24: below simplify_for_budget's reach
  replay.set_particle_count(chosen.front().particles);
  replay.initialize(frames[0].ground_truth);
  for (size_t i = 0; i < frames.size(); ++i) {
    INFO("frame " << i << ", " << chosen[i].particles << " particles");
    if (i > 0) replay.set_particle_count(chosen[i].particles);
    const Estimate e = replay.update(frames[i].depth, frames[i].timestamp);
    CHECK(e.particles == chosen[i].particles);
    CHECK(e.pose.translation == chosen[i].pose.translation);
    CHECK(e.pose.rotation.coeffs() == chosen[i].pose.rotation.coeffs());
    CHECK(e.effective_sample_size == chosen[i].effective_sample_size);
    CHECK(e.confidence == chosen[i].confidence);
    CHECK(e.status == chosen[i].status);
  }
}

TEST_CASE("without a budget every frame runs the configured count; a bad budget is refused", "[budget]") {
  const Mesh mesh = builtin_demo_mesh();
  const SynthConfig synth = test::small_scene(3);
  const auto frames = test::synthesize(mesh, synth);
  TrackerConfig config;
  config.particles = 30;
  Tracker tracker(mesh, synth.camera, config);
  tracker.initialize(frames[0].ground_truth);
  for (const SynthFrame& f : frames) CHECK(tracker.update(f.depth, f.timestamp).particles == 30);
  CHECK_THROWS_WITH(tracker.set_particle_count(31), Contains("[1, particles = 30]"));
  config.budget_ms = -1;
  CHECK_THROWS_WITH(config.validate(), Contains("frame budget"));
  config.budget_ms = 5;
  config.min_particles = 31;
  CHECK_THROWS_WITH(config.validate(), Contains("min particles 31") && Contains("particles = 30"));
  config.budget_ms = 0;  // without a budget the fewest is not used
  CHECK_NOTHROW(config.validate());
}
