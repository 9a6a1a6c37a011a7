#include "tracker/search_workers.hpp"

#include <algorithm>
#include <string>

#include "tracker/make_filter_backend.hpp"

namespace depthtrack {

int search_threads(const TrackerConfig& config) {
  const std::string backend = config.resolved_backend();
  if (backend == "reference") return 1;
  if (backend == "cpu" || backend.rfind("cpu:", 0) == 0) return cpu_backend_threads(backend);
  return hardware_threads();
}

struct SearchWorkers::Kit {
  Kit(const Mesh& mesh, const Camera& working, const TrackerConfig& config, const TrackerConfig& fit)
      : refiner(mesh, working, fit),
        rasterizer(mesh, working, config.near_plane, config.observation.max_depth),
        scratch(static_cast<size_t>(working.pixel_count())) {}
  reference::PoseRefiner refiner;
  reference::Rasterizer rasterizer;
  std::vector<float> scratch;
};

SearchWorkers::SearchWorkers(const Mesh& mesh, const Camera& working, const TrackerConfig& config,
                             const TrackerConfig& fit, int threads)
    : mesh_(mesh),
      working_(working),
      config_(config),
      fit_(fit),
      threads_(std::max(threads, 1)),
      kits_(static_cast<size_t>(threads_)) {}

SearchWorkers::~SearchWorkers() = default;

SearchWorkers::Kit& SearchWorkers::kit(int thread) {
  std::unique_ptr<Kit>& k = kits_[static_cast<size_t>(thread)];
  if (!k) k = std::make_unique<Kit>(mesh_, working_, config_, fit_);
  return *k;
}

ThreadPool* SearchWorkers::pool(size_t n) {
  if (threads_ == 1 || n < 2) return nullptr;
  if (!pool_) pool_ = std::make_unique<ThreadPool>(threads_);
  return pool_.get();
}

void SearchWorkers::each(size_t n, const std::function<void(size_t)>& item) {
  ThreadPool* threads = pool(n);
  if (!threads) {
    for (size_t i = 0; i < n; ++i) item(i);
    return;
  }
  run_ranges(*threads, n, [&](size_t, size_t first, size_t last, int) {
    for (size_t i = first; i < last; ++i) item(i);
  });
}

void SearchWorkers::run_with_kits(size_t n, const std::function<void(size_t, Kit&)>& task) {
  ThreadPool* threads = pool(n);
  if (!threads) {
    for (size_t i = 0; i < n; ++i) task(i, kit(0));
    return;
  }
  // Every thread's kit is made here, on the caller's thread: the tasks only read the vector of them.
  for (int t = 0; t < threads->size(); ++t) kit(t);
  threads->run(n, [&](size_t i, int thread) { task(i, *kits_[static_cast<size_t>(thread)]); });
}

std::vector<Pose> SearchWorkers::fit(std::span<const Pose> starts, const DepthImage& working,
                                     std::span<const double> occlusion) {
  std::vector<Pose> out(starts.size());
  run_with_kits(starts.size(),
                [&](size_t i, Kit& k) { out[i] = k.refiner.refine(starts[i], working, occlusion).pose; });
  return out;
}

std::vector<SilhouetteShares> SearchWorkers::shares(std::span<const Pose> poses, const DepthImage& working) {
  std::vector<SilhouetteShares> out(poses.size());
  run_with_kits(poses.size(), [&](size_t i, Kit& k) {
    out[i] =
        silhouette_shares(k.rasterizer, config_.observation, config_.loss.pixel_sigmas, poses[i], working, k.scratch);
  });
  return out;
}

}  // namespace depthtrack
