#pragma once
// The refined pose's covariance from the fit's normal equations, with the axes the pixels cannot
// determine set apart. A flat face seen face-on says nothing about sliding along it or turning about
// its normal; a body of revolution nothing about turning about its axis. There H is singular up to
// rounding, and its inverse is whatever the rounding makes it: double and float disagreed on which
// axes blew up (NaN against 3 m).
//
// How: a Cholesky factorization of the unit-diagonal C = D^-1/2 H D^-1/2 that pivots on the most
// informative axis left (its Schur complement times H_ii, rotations counted in metres at the mesh's
// radius) and sets apart every axis whose Schur complement falls below 1 / kMaxVarianceInflation
// (the axes taken explain its column but for that share) or that H has nothing on (H_ii <= 0). Of a
// face's sliding and its depth, the depth is taken first and the sliding set apart. A set-apart axis
// gets +infinity on the diagonal and 0 elsewhere in its row and column; the others the inverse of
// their own block (their covariance with the set-apart axes held). Every backend's fit hands its H
// here (the device's in the estimate buffer: DT_EST_NORMAL), so there is one implementation, in double.
#include <Eigen/Core>

namespace depthtrack::model {

// An axis is set apart when the axes taken before it explain all but 1 / 1e3 of its column (R^2 above
// 0.999): the device's float sums of H still give a kept axis' variance to a few parts in a thousand.
constexpr double kMaxVarianceInflation = 1e3;

// radius: the mesh's, the length that turns a rotation into metres for the pivot's choice. NaN
// everywhere with fewer than 6 pixels (the fit had too few to say anything).
Eigen::Matrix<double, 6, 6> pose_covariance(const Eigen::Matrix<double, 6, 6>& h, int pixels, double radius);

}  // namespace depthtrack::model
