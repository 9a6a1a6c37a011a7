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
constexpr double kKeepShare = 0.8;   // a frame keeps at least this share of the last one's particles
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
                               const MotionModel& motion)
    : budget_ms_(budget_ms),
      min_(min_particles),
      max_(max_particles),
      lost_below_(lost_below),
      motion_(motion),
      last_(max_particles) {
  if (!(std::isfinite(budget_ms) && budget_ms > 0) || min_particles < 1 || max_particles < min_particles)
    throw InputError("particle budget needs a positive time and 1 <= min particles <= particles");
}

int ParticleBudget::afforded() const {
  return afforded_within(budget_ms_);
}

int ParticleBudget::afforded_within(double ms) const {
  if (!timed_ && !primed_) return max_;
  const double room = ms - fixed_ms_ - miss_ms_;
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
  if (!settling) wanted = std::max(wanted, static_cast<int>(std::ceil(kKeepShare * last_)));
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
  miss_ms_ = 0;
  primed_ = true;
}

void ParticleBudget::observe(const Estimate& e, const Eigen::Matrix<double, 6, 6>& fit_covariance) {
  if (settle_left_ > 0) --settle_left_;
  const bool initial_frame = std::exchange(initial_frame_, false);
  const StepTimings& t = e.timings;
  if (e.particles > 0) {
    const double loops_ms = t.propagate_ms + t.render_ms + t.weigh_ms + t.resample_ms;
    const double per = loops_ms / e.particles;
    const double fixed = std::max(0.0, t.total_ms - t.search_ms - loops_ms);
    if (std::isfinite(per) && std::isfinite(fixed)) {
      if (!timed_ && !primed_) {
        per_particle_ms_ = per;
        fixed_ms_ = fixed;
      } else {
        // The initial frame runs over the budget on purpose, sized by the prime alone: how far its time
        // was from the model's says nothing of the frames within the budget.
        const double predicted = fixed_ms_ + per_particle_ms_ * e.particles;
        const double miss = std::abs(t.total_ms - t.search_ms - predicted);
        if (!initial_frame) miss_ms_ += kSmoothing * (miss - miss_ms_);
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
  need_ = std::clamp((kConfident - e.confidence) / (kConfident - std::min(lost_below_, kConfident - 1e-3)), 0.0, 1.0);
  // A NaN ratio (no fit) adds nothing; +infinity (a direction set apart) the most.
  const double spread = fit_spread_ratio(fit_covariance, motion_);
  if (!std::isnan(spread))
    need_ = std::max(need_, std::clamp((spread - kFitSpreadFrom) / (kFitSpreadFull - kFitSpreadFrom), 0.0, 1.0));
}

}  // namespace depthtrack
