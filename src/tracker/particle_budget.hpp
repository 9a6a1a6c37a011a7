#pragma once
// Chooses each frame's particle count within a time budget (TrackerConfig::budget_ms): how many the
// budget affords, from the tracker's own measured times, and how many the estimate needs, from its state.
//   afforded: a frame takes about fixed + fit + n * per_particle ms. per_particle is the particle loops'
//     time (propagate, render, weigh, resample) over their count, fit the refinement's, fixed the rest
//     (the confidence, the estimate's reading), a search excepted (it has its own budget,
//     RecoveryModel::budget_ms); each smoothed over frames, but a frame slower a particle than the model
//     sets per_particle at once. Frames vary about the model (the core's
//     caches, the draws' pixels): room is kept for the frames' overruns of it, kOverrunSpread times their
//     root mean square over about the last twenty frames (only overruns: a GPU's frames, which the
//     model overstates while the count climbs, keep none), so that about 95 % of frames end within the
//     budget. The first frame timed (its first touches of memory) and the frame after initialize() leave
//     it as it was; one frame's overrun counts as at most kOverrunClamp of that root mean square, or a
//     tenth of the budget where that is more (another process's time slice is not the model's spread). The fit stops
//     when it converges, after at most fit_steps steps, and how many a frame takes is not known before it: room is kept
//     for all fit_steps at the smoothed time of one step, so that a frame whose fit runs long still ends within the
//     budget.
//   needed: the fewest (min_particles) while the estimate is confident (kConfident and above), rising
//     linearly to the most (particles) as the confidence falls to loss.lost_below; the most while lost,
//     on a frame that starts a new cloud (initialization, a gap, a search's re-seed) and the few frames
//     after it, while the new cloud settles. And at least as many as the fit leaves to the particles: a
//     direction the fit determines less well than a frame of the motion model moves the particles is
//     found by the particles' draws, not by the fit (a mug's turn about its axis, seen by the handle's
//     few pixels): from the fit's spread there at one frame's motion noise (kFitSpreadFrom) the need rises
//     linearly to the most at twice it (kFitSpreadFull). It falls by at most a fifth a frame, so that one
//     good frame does not thin a cloud that is still finding its pose; where the range from the fewest to
//     the most is wider than a fifth a frame crosses in 14 frames (a GPU's), by as much as crosses it in 14.
// The count is the lesser of the two, within [min_particles, particles]: a budget too small for
// min_particles runs min_particles. Before any frame is timed: what prime's measured particle affords,
// or without it the fewest (that frame's time then sizes the next). The frame after initialize() from a
// pose and a spread is the exception: it runs what a search's budget affords (next_initial).
#include <Eigen/Core>
#include <cmath>
#include <depthtrack/tracker.hpp>

namespace depthtrack {

class ParticleBudget {
 public:
  // budget_ms > 0; 1 <= min_particles <= max_particles; motion: the filter's (its noise per reference frame
  // is what the fit's spread is compared with); fit_steps >= 0: the most steps a frame's fit can take (0:
  // no room kept for them beyond what the frames' fixed time holds).
  ParticleBudget(double budget_ms, int min_particles, int max_particles, double lost_below,
                 const MotionModel& motion = MotionModel{}, int fit_steps = 0);

  // The next frame's count. reseed: that frame starts from a new cloud.
  int next(bool reseed);
  // The count of the frame after initialize() from a pose and a spread: what search_ms (a search's
  // budget, RecoveryModel::budget_ms) affords, at most particles; the next call of next(false) returns it
  // again (that frame's own choice), and the cloud then settles as after next(true). That frame's time
  // moves the model's times as any frame's, but not its overruns (it ran over the budget on purpose).
  // That frame's weighing searches the spread for the pose, as a search does: the fewer a frame's budget
  // affords leave the spread's cloud too sparse (the YCB mug started 1 cm / 5 degrees off: 4-5 mm ADD-S
  // on its first frames from 48 particles, 1.2-1.5 mm from 200). A cloud of a search's or a gap's seeds,
  // spread narrowly, runs next(true).
  int next_initial(double search_ms);
  // What the frame just run took and said (its particles, timings, confidence and status), and the fit's
  // own covariance (the refinement's, before the tracker calibrates it for the report; NaN without a fit).
  // frame_confidence: the frame's own (pose_confidence of its evidence), how hard this frame is whatever
  // the run before it says; e.confidence where it is not given.
  void observe(const Estimate& e, const Eigen::Matrix<double, 6, 6>& fit_covariance, double frame_confidence);
  void observe(const Estimate& e, const Eigen::Matrix<double, 6, 6>& fit_covariance) {
    observe(e, fit_covariance, e.confidence);
  }
  void observe(const Estimate& e) { observe(e, Eigen::Matrix<double, 6, 6>::Constant(std::nan(""))); }
  // Before the first frame: one particle's time measured outside the frames (a drawing and weighing of
  // the start pose). Until a frame is timed the model is that per particle and kPrimedFixed of it fixed
  // (the fit's and the confidence's drawings), and the frames' times are smoothed into it as into a
  // timed model (a first frame slowed by its first touches of memory moves it a quarter). Ignored once
  // a frame was observed, or when not positive and finite.
  void prime(double per_particle_ms);
  bool timed() const { return timed_; }

  // The smoothed time model (ms); 0 before the first frame unless primed. fixed_ms holds the fit's time
  // until a frame reports its fit's steps (Estimate::refine_iterations), then fit_step_ms does.
  double per_particle_ms() const { return per_particle_ms_; }
  double fixed_ms() const { return fixed_ms_; }
  double fit_step_ms() const { return fit_step_ms_; }
  // The most particles the budget affords now (max_particles before the first frame unless primed).
  int afforded() const;
  // The same within ms instead of the budget.
  int afforded_within(double ms) const;

  static constexpr double kConfident = 0.9;    // from this confidence up, min_particles
  static constexpr int kSettleFrames = 3;      // frames after a new cloud that run what the budget affords
  static constexpr double kPrimedFixed = 10;   // the primed fixed time, in particles' times
  static constexpr double kFitSpreadFrom = 1;  // fit spread / motion noise from which the need rises
  static constexpr double kFitSpreadFull = 2;  // and at which it is the most
  // Overruns: a frame's weight in their mean square (about twenty frames), the room kept in root mean
  // squares of them (misses spread normally: their half above the model has root mean square 0.707 sigma,
  // and 95 % lie below 1.645 sigma), and one frame's most in root mean squares.
  static constexpr double kOverrunSmoothing = 0.1;
  static constexpr double kOverrunSpread = 2.326;
  static constexpr double kOverrunClamp = 3;
  // The room kept for overruns now (ms).
  double overrun_room_ms() const { return kOverrunSpread * std::sqrt(overrun_square_); }

 private:
  double budget_ms_;
  int min_, max_;
  double lost_below_;
  MotionModel motion_;
  int fit_steps_;
  bool timed_ = false;   // a frame has been observed
  bool primed_ = false;  // prime gave the model (until timed_)
  double per_particle_ms_ = 0, fixed_ms_ = 0, fit_step_ms_ = 0;
  double overrun_square_ = 0;   // smoothed square of the frames' overruns of the model (ms^2)
  bool fit_timed_ = false;      // a frame reported its fit's steps and time
  double need_ = 1;             // the last frame's need, 0 (min_particles) to 1 (particles)
  int settle_left_ = 0;         // frames still settling after a new cloud (observe counts them)
  int last_ = 0;                // the count last chosen
  int initial_ = 0;             // next_initial's count, for the next frame (0: none pending)
  bool initial_frame_ = false;  // the frame last chosen ran next_initial's count (observe reads it)
};

// How far the fit leaves the pose to the particles: the largest standard deviation of the fit's
// covariance over the per-frame motion noise, the translations' over sigma_linear and the rotations'
// over sigma_angular (the larger of the two). +infinity where the fit sets a direction apart
// (undetermined), NaN where it has no covariance (refinement off, too few pixels).
double fit_spread_ratio(const Eigen::Matrix<double, 6, 6>& fit_covariance, const MotionModel& motion);

}  // namespace depthtrack
