#pragma once
// Chooses each frame's particle count within a time budget (TrackerConfig::budget_ms): how many the
// budget affords, from the tracker's own measured times, and how many the estimate needs, from its state.
//   afforded: a frame takes about fixed + n * per_particle ms. per_particle is the particle loops' time
//     (propagate, render, weigh, resample) over their count, fixed the rest (refinement, confidence), a
//     search excepted (it has its own budget, RecoveryModel::budget_ms); both smoothed over frames, with
//     the smoothed size of the model's misses kept free.
//   needed: the fewest (min_particles) while the estimate is confident (kConfident and above), rising
//     linearly to the most (particles) as the confidence falls to loss.lost_below; the most while lost,
//     on a frame that starts a new cloud (initialization, a gap, a search's re-seed) and the few frames
//     after it, while the new cloud settles. It falls by at most a fifth a frame, so that one good frame
//     does not thin a cloud that is still finding its pose.
// The count is the lesser of the two, within [min_particles, particles]: a budget too small for
// min_particles runs min_particles. Before any frame is timed: what prime's measured particle affords,
// or without it the fewest (that frame's time then sizes the next).
#include <depthtrack/tracker.hpp>

namespace depthtrack {

class ParticleBudget {
 public:
  // budget_ms > 0; 1 <= min_particles <= max_particles.
  ParticleBudget(double budget_ms, int min_particles, int max_particles, double lost_below);

  // The next frame's count. reseed: that frame starts from a new cloud.
  int next(bool reseed);
  // What the frame just run took and said (its particles, timings, confidence and status).
  void observe(const Estimate& e);
  // Before the first frame: one particle's time measured outside the frames (a drawing and weighing of
  // the start pose). Until a frame is timed the model is that per particle and kPrimedFixed of it fixed
  // (the fit's and the confidence's drawings), and the frames' times are smoothed into it as into a
  // timed model (a first frame slowed by its first touches of memory moves it a quarter). Ignored once
  // a frame was observed, or when not positive and finite.
  void prime(double per_particle_ms);
  bool timed() const { return timed_; }

  // The smoothed time model (ms); 0 before the first frame unless primed.
  double per_particle_ms() const { return per_particle_ms_; }
  double fixed_ms() const { return fixed_ms_; }
  // The most particles the budget affords now (max_particles before the first frame unless primed).
  int afforded() const;

  static constexpr double kConfident = 0.9;   // from this confidence up, min_particles
  static constexpr int kSettleFrames = 3;     // frames after a new cloud that run what the budget affords
  static constexpr double kPrimedFixed = 10;  // the primed fixed time, in particles' times

 private:
  double budget_ms_;
  int min_, max_;
  double lost_below_;
  bool timed_ = false;   // a frame has been observed
  bool primed_ = false;  // prime gave the model (until timed_)
  double per_particle_ms_ = 0, fixed_ms_ = 0, miss_ms_ = 0;
  double need_ = 1;      // the last frame's need, 0 (min_particles) to 1 (particles)
  int settle_left_ = 0;  // frames still settling after a new cloud (observe counts them)
  int last_ = 0;         // the count last chosen
};

}  // namespace depthtrack
