#include <depthtrack/evaluation.hpp>
#include <nanoflann.hpp>

namespace depthtrack {

namespace {
// nanoflann's view of a point array.
struct PointCloud {
  const std::vector<Eigen::Vector3d>* points;
  size_t kdtree_get_point_count() const { return points->size(); }
  double kdtree_get_pt(size_t i, size_t dim) const { return (*points)[i][static_cast<Eigen::Index>(dim)]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};
using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, PointCloud>, PointCloud, 3>;
}  // namespace

// The tree holds the model's vertices in the object frame; a query maps the estimate's vertex into
// the truth's object frame, which leaves distances unchanged.
struct AddsMetric::Index {
  PointCloud cloud;
  KdTree tree;
  explicit Index(const std::vector<Eigen::Vector3d>& v)
      : cloud{&v}, tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16)) {
    tree.buildIndex();
  }
};

AddsMetric::AddsMetric(const Mesh& mesh) {
  vertices_.reserve(mesh.vertices.size());
  for (const auto& v : mesh.vertices) vertices_.push_back(v.cast<double>());
  index_ = std::make_unique<Index>(vertices_);
}

AddsMetric::~AddsMetric() = default;

double AddsMetric::operator()(const Pose& estimate, const Pose& truth) const {
  const Pose truth_from_estimate = truth.inverse() * estimate;
  double sum = 0;
  for (const auto& v : vertices_) {
    const Eigen::Vector3d q = truth_from_estimate.apply(v);
    uint32_t nearest = 0;
    double squared = 0;
    index_->tree.knnSearch(q.data(), 1, &nearest, &squared);
    sum += std::sqrt(squared);
  }
  return sum / static_cast<double>(vertices_.size());
}

}  // namespace depthtrack
