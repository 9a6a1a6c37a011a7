#include <Eigen/Geometry>
#include <cmath>
#include <depthtrack/error.hpp>
#include <depthtrack/mesh.hpp>
#include <string>

namespace depthtrack {

void Mesh::validate_and_clean(const std::string& what) {
  if (vertices.empty() || triangles.empty()) throw InputError(what + ": mesh is empty (no triangles)");
  for (size_t i = 0; i < vertices.size(); ++i)
    if (!vertices[i].allFinite())
      throw InputError(what + ": vertex " + std::to_string(i) + " has a non-finite coordinate");
  const float extent = (radius() > 0) ? radius() : 1.0f;
  // Relative to the mesh's size so that millimetre and metre meshes are judged alike.
  const float min_double_area = 1e-12f * extent * extent;
  std::vector<Eigen::Vector3i> kept;
  kept.reserve(triangles.size());
  for (size_t i = 0; i < triangles.size(); ++i) {
    const auto& t = triangles[i];
    for (int k = 0; k < 3; ++k)
      if (t[k] < 0 || static_cast<size_t>(t[k]) >= vertices.size())
        throw InputError(what + ": triangle " + std::to_string(i) + " refers to vertex " + std::to_string(t[k]) +
                         " of " + std::to_string(vertices.size()));
    const Eigen::Vector3f a = vertices[static_cast<size_t>(t[0])], b = vertices[static_cast<size_t>(t[1])],
                          c = vertices[static_cast<size_t>(t[2])];
    if ((b - a).cross(c - a).norm() > min_double_area) kept.push_back(t);
  }
  dropped_degenerate += triangles.size() - kept.size();
  if (kept.empty())
    throw InputError(what + ": all " + std::to_string(triangles.size()) +
                     " triangles are degenerate (zero area): nothing to render");
  triangles = std::move(kept);
}

Eigen::Vector3f Mesh::centre() const {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const auto& v : vertices) sum += v.cast<double>();
  return vertices.empty() ? Eigen::Vector3f::Zero()
                          : Eigen::Vector3f((sum / static_cast<double>(vertices.size())).cast<float>());
}

float Mesh::radius() const {
  const Eigen::Vector3f c = centre();
  float r = 0;
  for (const auto& v : vertices) r = std::max(r, (v - c).norm());
  return r;
}

Mesh make_box(const Eigen::Vector3f& size, const Eigen::Vector3f& centre) {
  Mesh m;
  for (int i = 0; i < 8; ++i)
    m.vertices.emplace_back(centre + 0.5f * Eigen::Vector3f((i & 1) ? size.x() : -size.x(),
                                                            (i & 2) ? size.y() : -size.y(),
                                                            (i & 4) ? size.z() : -size.z()));
  // Two triangles per face, wound outwards.
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    m.triangles.emplace_back(f[0], f[1], f[2]);
    m.triangles.emplace_back(f[0], f[2], f[3]);
  }
  return m;
}

void append_mesh(Mesh& mesh, const Mesh& other) {
  const int offset = static_cast<int>(mesh.vertices.size());
  mesh.vertices.insert(mesh.vertices.end(), other.vertices.begin(), other.vertices.end());
  for (const auto& t : other.triangles) mesh.triangles.emplace_back(t.array() + offset);
}

Mesh builtin_demo_mesh() {
  // A block with an offset handle on top: no rotational symmetry, so every pose is observable.
  Mesh m = make_box({0.16f, 0.05f, 0.06f});
  append_mesh(m, make_box({0.05f, 0.04f, 0.05f}, {0.045f, -0.045f, 0.0f}));
  return m;
}

}  // namespace depthtrack
