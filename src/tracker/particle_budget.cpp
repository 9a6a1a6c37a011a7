#include "tracker/particle_budget.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <depthtrack/error.hpp>
#include <limits>
#include <utility>

namespace depthtrack {

namespace {
constexpr double kSmoothing = 0.25;  // weight of the newest frame in the smoothed times
// A frame keeps at least this share of the last one's particles: a fifth less a frame, or less where the
// range from the fewest to the most is so wide that a fifth a frame would take more than kThinFrames
// frames to cross it (a GPU's 100,000 down to 10), so that a confident cloud thins in as many frames on
// any device.
constexpr double kKeepShare = 0.8;
constexpr double kThinFrames = 14;
double keep_share(int fewest, int most) {
  return std::min(kKeepShare, std::pow(static_cast<double>(fewest) / most, 1.0 / kThinFrames));
}
}  // namespace

double fit_spread_ratio(const Eigen::Matrix<double, 6, 6>& fit_covariance, const MotionModel& motion) {
  if (fit_covariance.array().isNaN().any()) return std::nan("");
  if (!fit_covariance.diagonal().array().isFinite().all()) return std::numeric_limits<double>::infinity();
  // The largest standard deviation of a 3 x 3 block over its noise; the block's eigenvalues, not its
  // diagonal: the weak direction need not be an axis of the camera.
  const auto spread = [&](int first, double sigma) {
    const Eigen::Matrix3d block = fit_covariance.block<3, 3>(first, first);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(block, Eigen::EigenvaluesOnly);
    const double largest = std::sqrt(std::max(0.0, solver.eigenvalues()(2)));
    return sigma > 0 ? largest / sigma : std::numeric_limits<double>::infinity();
  };
  return std::max(spread(0, motion.sigma_linear), spread(3, motion.sigma_angular));
}

ParticleBudget::ParticleBudget(double budget_ms, int min_particles, int max_particles, double lost_below,
                               const MotionModel& motion, int fit_steps)
    : budget_ms_(budget_ms),
      min_(min_particles),
      max_(max_particles),
      lost_below_(lost_below),
      motion_(motion),
      fit_steps_(fit_steps),
      last_(max_particles) {
  if (!(std::isfinite(budget_ms) && budget_ms > 0) || min_particles < 1 || max_particles < min_particles ||
      fit_steps < 0)
    throw InputError("particle budget needs a positive time, 1 <= min particles <= particles and fit steps >= 0");
}

int ParticleBudget::afforded() const {
  return afforded_within(budget_ms_);
}

int ParticleBudget::afforded_within(double ms) const {
  if (!timed_ && !primed_) return max_;
  const double room = ms - fixed_ms_ - fit_step_ms_ * fit_steps_ - overrun_room_ms();
  if (!(per_particle_ms_ > 0)) return max_;
  const double n = std::floor(room / per_particle_ms_);
  return n >= max_ ? max_ : n <= 0 ? 0 : static_cast<int>(n);
}

int ParticleBudget::next(bool reseed) {
  // The frame after next_initial runs its count, unless it starts another cloud.
  const int initial = std::exchange(initial_, 0);
  if (initial > 0 && !reseed) {
    initial_frame_ = true;
    return last_ = initial;
  }
  if (reseed) settle_left_ = kSettleFrames + 1;  // the new cloud's frame and kSettleFrames after it
  const bool settling = settle_left_ > 0;
  const double need = settling ? 1.0 : need_;
  int wanted = min_ + static_cast<int>(std::lround(need * (max_ - min_)));
  if (!settling) wanted = std::max(wanted, static_cast<int>(std::ceil(keep_share(min_, max_) * last_)));
  // Before any frame is timed and unprimed, the first runs the fewest: its time then sizes the next.
  const int afforded_now = timed_ || primed_ ? afforded() : min_;
  last_ = std::clamp(std::min(wanted, afforded_now), min_, max_);
  return last_;
}

int ParticleBudget::next_initial(double search_ms) {
  next(true);
  last_ = std::clamp(afforded_within(search_ms), min_, max_);
  initial_ = last_;
  return last_;
}

void ParticleBudget::prime(double per_particle_ms) {
  if (timed_ || !(std::isfinite(per_particle_ms) && per_particle_ms > 0)) return;
  per_particle_ms_ = per_particle_ms;
  fixed_ms_ = kPrimedFixed * per_particle_ms;
  overrun_square_ = 0;
  primed_ = true;
}

void ParticleBudget::observe(const Estimate& e, const Eigen::Matrix<double, 6, 6>& fit_covariance,
                             double frame_confidence) {
  if (settle_left_ > 0) --settle_left_;
  const bool initial_frame = std::exchange(initial_frame_, false);
  const StepTimings& t = e.timings;
  if (e.particles > 0) {
    const double loops_ms = t.propagate_ms + t.render_ms + t.weigh_ms + t.resample_ms;
    const double per = loops_ms / e.particles;
    // With its steps counted the fit is modelled apart, by the step (the frame's fit ran this many: the
    // prediction below uses them, so an overrun is the model's, not the fit's varying length).
    const bool fit_counted = fit_steps_ > 0 && e.refine_iterations > 0 && std::isfinite(t.refine_ms);
    const double fit_ms = fit_counted ? t.refine_ms : 0.0;
    const double step = fit_counted ? t.refine_ms / e.refine_iterations : 0.0;
    const double fixed = std::max(0.0, t.total_ms - t.search_ms - loops_ms - fit_ms);
    if (std::isfinite(per) && std::isfinite(fixed)) {
      if (fit_counted && !fit_timed_) {
        fit_step_ms_ = step;
        fit_timed_ = true;
        // The fixed time held the fit until now: from here it holds the rest alone.
        if (timed_ || primed_) fixed_ms_ = std::max(0.0, fixed_ms_ - fit_ms);
      } else if (fit_counted) {
        fit_step_ms_ += kSmoothing * (step - fit_step_ms_);
      }
      if (!timed_ && !primed_) {
        per_particle_ms_ = per;
        fixed_ms_ = fixed;
      } else {
        // The initial frame runs over the budget on purpose, sized by the prime alone, and the first
        // frame touches its memory first: how far their times were from the model's says nothing of the
        // frames within the budget.
        const double predicted = fixed_ms_ + fit_ms + per_particle_ms_ * e.particles;
        if (!initial_frame && timed_) {
          const double most = std::max(kOverrunClamp * std::sqrt(overrun_square_), 0.1 * budget_ms_);
          const double overrun = std::clamp(t.total_ms - t.search_ms - predicted, 0.0, most);
          overrun_square_ += kOverrunSmoothing * (overrun * overrun - overrun_square_);
        }
        // A frame slower a particle than the model sets it at once (the core slowed, the object came
        // nearer: while a smoothed model caught up, the next frames would overrun too); a faster one
        // moves it a quarter, as do the first and the initial frame.
        if (per > per_particle_ms_ && timed_ && !initial_frame)
          per_particle_ms_ = per;
        else
          per_particle_ms_ += kSmoothing * (per - per_particle_ms_);
        fixed_ms_ += kSmoothing * (fixed - fixed_ms_);
      }
      timed_ = true;
    }
  }
  if (e.status == TrackStatus::NoData) return;  // nothing seen: the need stays
  if (e.status == TrackStatus::Lost || e.recovered) {
    need_ = 1;
    return;
  }
  need_ =
      std::clamp((kConfident - frame_confidence) / (kConfident - std::min(lost_below_, kConfident - 1e-3)), 0.0, 1.0);
  // A NaN ratio (no fit) adds nothing; +infinity (a direction set apart) the most.
  const double spread = fit_spread_ratio(fit_covariance, motion_);
  if (!std::isnan(spread))
    need_ = std::max(need_, std::clamp((spread - kFitSpreadFrom) / (kFitSpreadFull - kFitSpreadFrom), 0.0, 1.0));
}

}  // namespace depthtrack
