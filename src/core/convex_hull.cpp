#include "core/convex_hull.hpp"

#include <algorithm>
#include <cstdio>
#include <memory>

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

namespace depthtrack {

namespace {
// Qhull writes its diagnostics to a stream; a flat or degenerate mesh is an expected case here (the
// caller falls back), so they go nowhere.
struct FileCloser {
  void operator()(FILE* f) const { std::fclose(f); }
};
}  // namespace

std::optional<std::vector<int>> convex_hull_vertices(const std::vector<Eigen::Vector3f>& points) {
  if (points.size() < 4) return std::nullopt;
  std::vector<coordT> coordinates;
  coordinates.reserve(3 * points.size());
  for (const auto& p : points) {
    if (!p.allFinite()) return std::nullopt;
    coordinates.insert(coordinates.end(), {p.x(), p.y(), p.z()});
  }
  const std::unique_ptr<FILE, FileCloser> quiet(std::fopen("/dev/null", "w"));
  qhT state;
  qhT* qh = &state;
  qh_zero(qh, quiet.get());
  // Qhull's defaults: nearly coplanar facets are merged, so a point on a flat face is no vertex.
  char options[] = "qhull";
  const int failed =
      qh_new_qhull(qh, 3, static_cast<int>(points.size()), coordinates.data(), False, options, nullptr, quiet.get());
  std::optional<std::vector<int>> indices;
  if (!failed) {
    indices.emplace();
    vertexT* vertex;
    FORALLvertices indices->push_back(qh_pointid(qh, vertex->point));
    std::sort(indices->begin(), indices->end());
  }
  qh_freeqhull(qh, !qh_ALL);
  int long_left = 0, long_bytes = 0;
  qh_memfreeshort(qh, &long_left, &long_bytes);
  return indices;
}

}  // namespace depthtrack
