#include "core/mesh_simplify.hpp"

#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <depthtrack/error.hpp>
#include <limits>
#include <string>
#include <vector>

namespace depthtrack {

double drawing_error(const Mesh& mesh, double simplify_error) {
  return std::min(simplify_error, kMaxRadiusShare * static_cast<double>(mesh.radius()));
}

MeshSimplification simplify_for_drawing(const Mesh& mesh, double simplify_error) {
  return simplify_within(mesh, drawing_error(mesh, simplify_error));
}

MeshSimplification simplify_for_budget(const Mesh& mesh, double simplify_error) {
  MeshSimplification drawn = simplify_for_drawing(mesh, simplify_error);
  if (simplify_error == 0 || drawn.mesh.triangles.size() <= kBudgetTriangles) return drawn;
  MeshSimplification coarser =
      simplify_within(mesh, kMaxRadiusShare * static_cast<double>(mesh.radius()), kBudgetTriangles);
  return coarser.mesh.triangles.size() < drawn.mesh.triangles.size() ? coarser : drawn;
}

MeshSimplification simplify_within(const Mesh& mesh, double max_error, size_t target_triangles) {
  if (!std::isfinite(max_error) || max_error < 0)
    throw InputError("mesh simplification error " + std::to_string(max_error) + " m must be finite and >= 0");
  MeshSimplification result{mesh, 0.0, mesh.triangles.size()};
  if (max_error == 0 || mesh.triangles.empty()) return result;
  std::vector<float> positions;
  positions.reserve(3 * mesh.vertices.size());
  for (const Eigen::Vector3f& v : mesh.vertices) positions.insert(positions.end(), {v.x(), v.y(), v.z()});
  std::vector<unsigned> indices;
  indices.reserve(3 * mesh.triangles.size());
  for (const Eigen::Vector3i& t : mesh.triangles)
    indices.insert(indices.end(), {static_cast<unsigned>(t.x()), static_cast<unsigned>(t.y()), static_cast<unsigned>(t.z())});
  // meshoptimizer's error is relative to the mesh's extent.
  const float scale = meshopt_simplifyScale(positions.data(), mesh.vertices.size(), 3 * sizeof(float));
  if (!(scale > 0)) return result;
  std::vector<unsigned> kept(indices.size());
  float relative_error = 0;
  const size_t kept_count =
      meshopt_simplify(kept.data(), indices.data(), indices.size(), positions.data(), mesh.vertices.size(),
                       3 * sizeof(float), 3 * target_triangles, static_cast<float>(max_error / scale), 0,
                       &relative_error);
  if (kept_count == 0) return result;  // nothing would be left: draw the mesh as given
  // Only the vertices still used, in their first use's order.
  std::vector<int> renumbered(mesh.vertices.size(), -1);
  Mesh simplified;
  simplified.dropped_degenerate = mesh.dropped_degenerate;
  for (size_t i = 0; i < kept_count; i += 3) {
    Eigen::Vector3i triangle;
    for (int c = 0; c < 3; ++c) {
      int& index = renumbered[kept[i + static_cast<size_t>(c)]];
      if (index < 0) {
        index = static_cast<int>(simplified.vertices.size());
        simplified.vertices.push_back(mesh.vertices[kept[i + static_cast<size_t>(c)]]);
      }
      triangle[c] = index;
    }
    simplified.triangles.push_back(triangle);
  }
  result.mesh = std::move(simplified);
  result.error = static_cast<double>(relative_error) * static_cast<double>(scale);
  return result;
}

}  // namespace depthtrack
