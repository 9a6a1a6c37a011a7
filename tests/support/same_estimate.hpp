#pragma once
// Two trackers that must have computed the same frame: the same pose, effective sample size,
// confidence and status, bit for bit (a shared Device, a view in place of an image, ...).
#include <catch2/catch.hpp>
#include <depthtrack/tracker.hpp>

namespace depthtrack::test {

inline void require_same_estimate(const Estimate& a, const Estimate& b) {
  REQUIRE(a.pose.translation == b.pose.translation);
  REQUIRE(a.pose.rotation.coeffs() == b.pose.rotation.coeffs());
  REQUIRE(a.effective_sample_size == b.effective_sample_size);
  REQUIRE(a.confidence == b.confidence);
  REQUIRE(a.status == b.status);
}

}  // namespace depthtrack::test
