#include "core/mesh_topology.hpp"

#include <Eigen/Geometry>
#include <cstdint>
#include <numeric>
#include <unordered_map>
#include <vector>

namespace depthtrack {

namespace {
std::uint64_t edge_key(int low, int high) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(low)) << 32) | static_cast<std::uint32_t>(high);
}

// Union-find over vertices: the connected parts of the mesh.
struct Parts {
  std::vector<int> parent;
  explicit Parts(size_t count) : parent(count) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int i) {
    while (parent[static_cast<size_t>(i)] != i)
      i = parent[static_cast<size_t>(i)] = parent[static_cast<size_t>(parent[static_cast<size_t>(i)])];
    return i;
  }
  void join(int a, int b) { parent[static_cast<size_t>(find(a))] = find(b); }
};
}  // namespace

bool bounds_solid_outward(const Mesh& mesh) {
  if (mesh.triangles.empty()) return false;
  const int vertex_count = static_cast<int>(mesh.vertices.size());
  for (const Eigen::Vector3i& t : mesh.triangles)
    if ((t.array() < 0).any() || (t.array() >= vertex_count).any()) return false;
  // Each directed edge counts +1 and its reverse -1 (keyed by the edge from the smaller index): a closed,
  // consistently wound surface leaves every count at 0.
  std::unordered_map<std::uint64_t, int> balance;
  balance.reserve(mesh.triangles.size() * 3 / 2 + 1);
  Parts parts(mesh.vertices.size());
  for (const Eigen::Vector3i& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const int from = t[k], to = t[(k + 1) % 3];
      if (from < to)
        ++balance[edge_key(from, to)];
      else
        --balance[edge_key(to, from)];
      parts.join(from, to);
    }
  for (const auto& [edge, count] : balance)
    if (count != 0) return false;
  // Six times each part's signed volume: the sum of a . (b x c) over its triangles.
  std::unordered_map<int, double> volume;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices[static_cast<size_t>(t[0])].cast<double>(),
                          b = mesh.vertices[static_cast<size_t>(t[1])].cast<double>(),
                          c = mesh.vertices[static_cast<size_t>(t[2])].cast<double>();
    volume[parts.find(t[0])] += a.dot(b.cross(c));
  }
  for (const auto& [part, six_volume] : volume)
    if (!(six_volume > 0)) return false;
  return true;
}

}  // namespace depthtrack
