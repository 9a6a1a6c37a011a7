// The likelihood and occlusion formulas against the hand-computed values of MODEL.md.
#include <catch2/catch.hpp>

#include "model/occlusion_chain.hpp"
#include "reference/observation_model.hpp"

using namespace depthtrack;
using namespace depthtrack::reference;
using namespace depthtrack::model;

TEST_CASE("depth noise grows with the square of the observed depth", "[model]") {
  const ObservationModel m;
  CHECK(depth_sigma(m, 1.0) == Approx(0.0044247));
  CHECK(depth_sigma(m, 2.0) == Approx(0.003 + 4 * 0.0014247));
}

TEST_CASE("log-ratio matches MODEL.md's reference values at y = 1 m, p = 0.1", "[model]") {
  const ObservationModel m;
  // Object seen where it is rendered.
  CHECK(pixel_log_ratio(pixel_densities(m, 1.0, 1.0), 0.1) == Approx(5.45).margin(0.005));
  // Something 2 cm in front of the object.
  CHECK(pixel_log_ratio(pixel_densities(m, 0.98, 1.0), 0.1) == Approx(-1.56).margin(0.005));
  // Seeing behind the object: impossible if it were there, only the outlier tail explains it.
  CHECK(pixel_log_ratio(pixel_densities(m, 1.3, 1.0), 0.1) == Approx(-5.1).margin(0.05));
}

TEST_CASE("pixel densities by hand at y = y_hat = 1 m", "[model]") {
  const ObservationModel m;
  const PixelDensities d = pixel_densities(m, 1.0, 1.0);
  const double sigma = 0.0044247;
  // w/D + (1-w) N(0; 0, sigma^2)
  CHECK(d.visible == Approx(0.01 / 6 + 0.99 / (std::sqrt(2 * M_PI) * sigma)).epsilon(1e-12));
  // p_bg = w/D + (1-w) lambda exp(-lambda y + lambda^2 sigma^2 / 2), lambda = ln 2
  const double lambda = std::log(2.0);
  CHECK(d.background == Approx(0.01 / 6 + 0.99 * lambda * std::exp(-lambda + lambda * lambda * sigma * sigma / 2)));
  // At y = y_hat the occluder density is about half the truncated prior's value at y_hat.
  const double prior_at_y_hat = lambda * std::exp(0.0) / (std::exp(lambda) - 1.0);
  CHECK(d.occluded == Approx(0.01 / 6 + 0.99 * prior_at_y_hat * 0.5).epsilon(0.01));
}

TEST_CASE("no occlusion modelling: p = 0 gives log(p_vis / p_bg)", "[model]") {
  const ObservationModel m;
  const PixelDensities d = pixel_densities(m, 1.0, 1.0);
  CHECK(pixel_log_ratio(d, 0.0) == Approx(std::log(d.visible / d.background)));
}

TEST_CASE("Bayes update of the occlusion probability", "[model]") {
  const ObservationModel m;
  // An observation 20 cm in front of the rendered object: almost surely an occluder.
  const PixelDensities front = pixel_densities(m, 0.8, 1.0);
  const double p = occlusion_posterior(front, 0.1);
  CHECK(p == Approx(0.1 * front.occluded / (0.9 * front.visible + 0.1 * front.occluded)));
  CHECK(p > 0.95);  // 0.1 * 0.79 / (0.9 * 0.0017 + 0.1 * 0.79) = 0.98
  // The object seen where rendered: occlusion becomes unlikely.
  CHECK(occlusion_posterior(pixel_densities(m, 1.0, 1.0), 0.1) < 0.01);
  // By hand with made-up densities: 0.5 * 2 / (0.5 * 1 + 0.5 * 2) = 2/3.
  CHECK(occlusion_posterior(PixelDensities{1.0, 2.0, 1.0}, 0.5) == Approx(2.0 / 3.0));
}

TEST_CASE("occlusion chain: MODEL.md's one-frame steps and its fixed point", "[model]") {
  const OcclusionModel m;
  CHECK(occlusion_steady_state(m) == Approx(0.25));
  CHECK(propagate_occlusion(m, 0.1, 1.0 / 30) == Approx(0.1025).margin(5e-5));
  CHECK(propagate_occlusion(m, 0.9, 1.0 / 30) == Approx(0.889).margin(5e-4));
  // The recursion form of MODEL.md: 1 - [c^dt (1 - p) + (1 - a)(c^dt - 1)/(c - 1)].
  const double c = 0.6, dt = 0.37, p = 0.42;
  const double recursion = 1 - (std::pow(c, dt) * (1 - p) + (1 - 0.7) * (std::pow(c, dt) - 1) / (c - 1));
  CHECK(propagate_occlusion(m, p, dt) == Approx(recursion));
  // Two steps equal one step over the summed time: why both storage schemes agree.
  CHECK(propagate_occlusion(m, propagate_occlusion(m, p, 0.1), 0.25) == Approx(propagate_occlusion(m, p, 0.35)));
  CHECK(propagate_occlusion(m, p, 0.0) == Approx(p));
}

namespace {
// MODEL.md's formulas as written, in long double, whose exp reaches e^11356: the statement the scaled
// double implementation is checked against where double's exp would overflow.
long double naive_log_ratio(const ObservationModel& m, long double y, long double y_hat, long double p,
                            long double& posterior) {
  const long double sigma = m.sigma_constant + m.sigma_quadratic * y * y, lambda = m.occluder_rate;
  const long double tail = m.tail_weight / m.max_depth, keep = 1 - m.tail_weight, z = (y - y_hat) / sigma;
  const long double visible = tail + keep * std::exp(-0.5L * z * z) / (std::sqrt(2 * M_PIl) * sigma);
  const long double occluded =
      tail + keep * lambda * std::exp(lambda * (y_hat - y) + 0.5L * lambda * lambda * sigma * sigma) *
                 (1 + std::erf((y_hat - y + lambda * sigma * sigma) / (std::sqrt(2.0L) * sigma))) /
                 (2 * std::expm1(lambda * y_hat));
  const long double background = tail + keep * lambda * std::exp(-lambda * y + 0.5L * lambda * lambda * sigma * sigma);
  posterior = p * occluded / ((1 - p) * visible + p * occluded);
  return std::log(((1 - p) * visible + p * occluded) / background);
}
}  // namespace

TEST_CASE("log-ratio and posterior stay finite and exact for observations far beyond the sensor's range", "[model]") {
  // exp(lambda^2 sigma^2 / 2) overflows double from y ~ 250 m: the densities are scaled, not the ratio.
  ObservationModel m;
  for (const double y : {0.7, 5.0, 60.0, 150.0, 250.0, 300.0}) {  // beyond 320 m long double overflows too
    for (const double y_hat : {0.3, 1.0, 5.9}) {
      INFO("y " << y << " y_hat " << y_hat);
      const PixelDensities d = pixel_densities(m, y, y_hat);
      long double posterior = 0;
      const long double expected = naive_log_ratio(m, y, y_hat, 0.3L, posterior);
      REQUIRE(std::isfinite(pixel_log_ratio(d, 0.3)));
      CHECK(pixel_log_ratio(d, 0.3) == Approx(static_cast<double>(expected)).epsilon(1e-9).margin(1e-9));
      CHECK(occlusion_posterior(d, 0.3) == Approx(static_cast<double>(posterior)).epsilon(1e-9).margin(1e-12));
    }
  }
  for (const double y : {1e3, 1e5, 1e7}) {
    INFO("y " << y);
    CHECK(std::isfinite(pixel_log_ratio(pixel_densities(m, y, 1.0), 0.3)));
    CHECK(std::isfinite(occlusion_posterior(pixel_densities(m, y, 1.0), 0.3)));
  }
  // Within the range the densities are the unscaled ones.
  CHECK(pixel_densities(m, 5.0, 1.0).log_scale == 0.0);
  CHECK(pixel_densities(m, 300.0, 1.0).log_scale > 709);
}
