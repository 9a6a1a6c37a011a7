#include "search/simplify_mesh.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <tuple>

namespace depthtrack::search {

Mesh simplify_mesh(const Mesh& mesh, double cell) {
  if (!(cell > 0) || mesh.vertices.empty()) return mesh;
  // Cell of each vertex, and each cell's mean position.
  std::map<std::tuple<long, long, long>, int> cells;
  std::vector<int> cluster(mesh.vertices.size());
  std::vector<Eigen::Vector3d> sums;
  std::vector<int> counts;
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Eigen::Vector3f& v = mesh.vertices[i];
    const auto key = std::make_tuple(std::lround(std::floor(v.x() / cell)), std::lround(std::floor(v.y() / cell)),
                                     std::lround(std::floor(v.z() / cell)));
    const auto [it, fresh] = cells.emplace(key, static_cast<int>(sums.size()));
    if (fresh) {
      sums.emplace_back(Eigen::Vector3d::Zero());
      counts.push_back(0);
    }
    cluster[i] = it->second;
    sums[static_cast<size_t>(it->second)] += v.cast<double>();
    ++counts[static_cast<size_t>(it->second)];
  }
  Mesh out;
  for (size_t c = 0; c < sums.size(); ++c) out.vertices.push_back((sums[c] / counts[c]).cast<float>());
  std::set<std::array<int, 3>> seen;
  for (const auto& t : mesh.triangles) {
    const int a = cluster[static_cast<size_t>(t[0])], b = cluster[static_cast<size_t>(t[1])],
              c = cluster[static_cast<size_t>(t[2])];
    if (a == b || b == c || a == c) continue;
    std::array<int, 3> key{a, b, c};
    std::sort(key.begin(), key.end());
    if (seen.insert(key).second) out.triangles.emplace_back(a, b, c);
  }
  if (out.triangles.empty() || out.triangles.size() >= mesh.triangles.size()) return mesh;
  out.validate_and_clean("simplified search mesh");
  return out;
}

}  // namespace depthtrack::search
