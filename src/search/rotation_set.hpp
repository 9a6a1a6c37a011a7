#pragma once
// Deterministic rotation sets for global search.
#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

namespace depthtrack::search {

// n rotations spread evenly over SO(3): the super-Fibonacci spiral (Alexa, "Super-Fibonacci
// Spirals: Fast, Low-Discrepancy Sampling of SO(3)", CVPR 2022). Any n, no random numbers.
std::vector<Eigen::Quaterniond> uniform_rotations(size_t n);

// How many such rotations leave no rotation farther than `radius` radians from one of them: a
// geodesic ball of radius r holds (r - sin r) / pi of SO(3), and the spiral covers it about as
// evenly as a lattice, so n = 1.5 pi / (r - sin r) (the factor 1.5 allows for the overlap).
size_t rotations_for_radius(double radius);

}  // namespace depthtrack::search
