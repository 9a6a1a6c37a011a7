#include "core/mesh_symmetry.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <unordered_map>
#include <vector>

namespace depthtrack {
namespace {

using Vec3 = Eigen::Vector3d;

struct Facet {
  Vec3 centroid, normal;
  double area;
};

// Points within `cell` of a query, by a hash of cubes of that edge.
class PointGrid {
 public:
  PointGrid(const std::vector<Vec3>& points, double cell) : points_(points), cell_(cell) {
    for (size_t i = 0; i < points.size(); ++i) cells_[key(index(points[i]))].push_back(static_cast<uint32_t>(i));
  }
  bool near(const Vec3& q) const {
    const Eigen::Vector3i c = index(q);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = cells_.find(key(c + Eigen::Vector3i(dx, dy, dz)));
          if (it == cells_.end()) continue;
          for (uint32_t i : it->second)
            if ((points_[i] - q).squaredNorm() <= cell_ * cell_) return true;
        }
    return false;
  }

 private:
  Eigen::Vector3i index(const Vec3& p) const { return (p / cell_).array().floor().cast<int>(); }
  static int64_t key(const Eigen::Vector3i& c) {
    return (static_cast<int64_t>(c.x() & 0x1FFFFF) << 42) | (static_cast<int64_t>(c.y() & 0x1FFFFF) << 21) |
           static_cast<int64_t>(c.z() & 0x1FFFFF);
  }
  const std::vector<Vec3>& points_;
  double cell_;
  std::unordered_map<int64_t, std::vector<uint32_t>> cells_;
};

// The weighted least-squares axis of the facets' normals from a start, down-weighting facets whose normal
// misses the axis by more than three times the median miss (the parts that break the symmetry).
SymmetryAxis fit_from(const std::vector<Facet>& facets, Vec3 point, Vec3 direction) {
  std::vector<double> miss(facets.size()), weight(facets.size());
  for (int iteration = 0; iteration < 8; ++iteration) {
    for (size_t i = 0; i < facets.size(); ++i)
      miss[i] = std::abs(direction.dot(facets[i].normal.cross(facets[i].centroid - point)));
    std::vector<double> sorted = miss;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(sorted.size() / 2), sorted.end());
    const double scale = 3 * sorted[sorted.size() / 2] + 1e-12;
    double total = 0;
    for (size_t i = 0; i < facets.size(); ++i) {
      const double r = std::max(1.0, miss[i] / scale);
      weight[i] = facets[i].area / (r * r);
      total += weight[i];
    }
    // Direction: the least eigenvector of sum w g g^T, g = n x (x - p) (a . g = 0 on the axis).
    Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
    for (size_t i = 0; i < facets.size(); ++i) {
      const Vec3 g = facets[i].normal.cross(facets[i].centroid - point);
      m += weight[i] * g * g.transpose();
    }
    direction = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(m).eigenvectors().col(0).normalized();
    // Point: a . (n x (x - p)) = y - h . p with y = a . (n x x), h = a x n; its move along a held at 0.
    Eigen::Matrix3d a = total * direction * direction.transpose();
    Vec3 b = a * point;
    for (size_t i = 0; i < facets.size(); ++i) {
      const Vec3 h = direction.cross(facets[i].normal);
      a += weight[i] * h * h.transpose();
      b += weight[i] * h * direction.dot(facets[i].normal.cross(facets[i].centroid));
    }
    point = a.ldlt().solve(b);
  }
  return {point, direction, 0};
}

// The least share (by area) of the samples that turns about the axis map within the grid's cell of a sample.
double turned_share(const SymmetryAxis& axis, const std::vector<Vec3>& samples, const std::vector<double>& weights,
                    const PointGrid& grid) {
  double least = 1, total = 0;
  for (double w : weights) total += w;
  for (double degrees : {10.0, 30.0, 90.0}) {
    const Eigen::Matrix3d turn = Eigen::AngleAxisd(degrees * std::numbers::pi / 180, axis.direction).toRotationMatrix();
    double on = 0;
    for (size_t i = 0; i < samples.size(); ++i)
      if (grid.near(axis.point + turn * (samples[i] - axis.point))) on += weights[i];
    least = std::min(least, on / total);
  }
  return least;
}

}  // namespace

std::optional<SymmetryAxis> fit_symmetry_axis(const Mesh& mesh) {
  std::vector<Facet> facets;
  std::vector<Vec3> samples;
  std::vector<double> weights;
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY), centre = Vec3::Zero();
  double area = 0;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const Vec3 a = mesh.vertices[t[0]].cast<double>(), b = mesh.vertices[t[1]].cast<double>(),
               c = mesh.vertices[t[2]].cast<double>();
    const Vec3 cross = (b - a).cross(c - a);
    const double twice = cross.norm();
    if (!(twice > 0)) continue;
    facets.push_back({(a + b + c) / 3, cross / twice, twice / 2});
    // Four samples a facet: its centroid and its three corner sub-triangles' centroids.
    for (const Vec3& s :
         {Vec3((a + b + c) / 3), Vec3((2 * a + b + c) / 4), Vec3((a + 2 * b + c) / 4), Vec3((a + b + 2 * c) / 4)}) {
      samples.push_back(s);
      weights.push_back(twice / 8);
    }
    for (const Vec3& v : {a, b, c}) {
      lo = lo.cwiseMin(v);
      hi = hi.cwiseMax(v);
    }
    centre += twice / 2 * facets.back().centroid;
    area += twice / 2;
  }
  if (facets.empty()) return std::nullopt;
  centre /= area;
  Eigen::Matrix3d moment = Eigen::Matrix3d::Zero();
  for (const Facet& f : facets) moment += f.area * (f.centroid - centre) * (f.centroid - centre).transpose();
  const Eigen::Matrix3d starts = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(moment).eigenvectors();
  const double tolerance = kSymmetryTolerance * (hi - lo).norm();
  const PointGrid grid(samples, tolerance);
  // The turned points: at most kTurnedSamples of the samples, evenly through them (the grid keeps all).
  constexpr size_t kTurnedSamples = 8192;
  const size_t stride = (samples.size() + kTurnedSamples - 1) / kTurnedSamples;
  std::vector<Vec3> turned;
  std::vector<double> turned_weights;
  for (size_t i = 0; i < samples.size(); i += stride) {
    turned.push_back(samples[i]);
    turned_weights.push_back(weights[i]);
  }
  std::optional<SymmetryAxis> best;
  std::vector<SymmetryAxis> tried;
  for (int k = 0; k < 3; ++k) {  // each principal axis as a start: the fit usually ends on one axis from all
    SymmetryAxis axis = fit_from(facets, centre, starts.col(k));
    const bool seen = std::any_of(tried.begin(), tried.end(), [&](const SymmetryAxis& t) {
      const Vec3 off = axis.point - t.point;
      return std::abs(axis.direction.dot(t.direction)) > 0.9999 &&
             (off - off.dot(t.direction) * t.direction).norm() < 0.1 * tolerance;
    });
    if (seen) continue;
    tried.push_back(axis);
    axis.share = turned_share(axis, turned, turned_weights, grid);
    if (!best || axis.share > best->share) best = axis;
  }
  return best;
}

std::optional<SymmetryAxis> symmetry_axis(const Mesh& mesh) {
  std::optional<SymmetryAxis> axis = fit_symmetry_axis(mesh);
  if (axis && axis->share >= kSymmetricShare) return axis;
  return std::nullopt;
}

}  // namespace depthtrack
