#include "search/rotation_set.hpp"

#include <cmath>
#include <numbers>

namespace depthtrack::search {

std::vector<Eigen::Quaterniond> uniform_rotations(size_t n) {
  // The two irrational turns of the spiral: phi^2 = 2 and psi^4 = psi + 4 (Alexa 2022, eq. 9).
  constexpr double phi = 1.4142135623730951, psi = 1.533751168755204288118041;
  std::vector<Eigen::Quaterniond> out;
  out.reserve(n);
  for (size_t i = 0; i < n; ++i) {
    const double s = static_cast<double>(i) + 0.5, share = s / static_cast<double>(n);
    const double r = std::sqrt(share), big_r = std::sqrt(1.0 - share);
    const double alpha = 2.0 * std::numbers::pi * s / phi, beta = 2.0 * std::numbers::pi * s / psi;
    out.emplace_back(big_r * std::cos(beta), r * std::sin(alpha), r * std::cos(alpha), big_r * std::sin(beta));
    out.back().normalize();
  }
  return out;
}

size_t rotations_for_radius(double radius) {
  const double r = std::min(radius, std::numbers::pi);
  return static_cast<size_t>(std::ceil(1.5 * std::numbers::pi / (r - std::sin(r))));
}

}  // namespace depthtrack::search
