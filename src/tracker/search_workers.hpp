#pragma once
// The global search's host work split over threads: each best candidate's Gauss-Newton fit and
// silhouette, and each pose's agreement with a detector's box. Every item is computed alone, as the
// sequential loop computed it, so the results do not depend on the thread count. The threads follow
// the backend: 1 for `reference` (sequential by name), N for `cpu:N`, the host's for a device (its
// search scores on the device and waits for these).
#include <depthtrack/depth_image.hpp>
#include <depthtrack/mesh.hpp>
#include <depthtrack/tracker_config.hpp>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "core/thread_pool.hpp"
#include "reference/pose_refiner.hpp"
#include "reference/rasterizer.hpp"
#include "tracker/silhouette_shares.hpp"

namespace depthtrack {

// The threads the search's host work takes for config's backend (TrackerConfig::resolved_backend).
int search_threads(const TrackerConfig& config);

class SearchWorkers {
 public:
  // config: the tracker's (the silhouettes' model and band); fit: the fits' (reference::PoseRefiner's);
  // threads >= 1.
  SearchWorkers(const Mesh& mesh, const Camera& working, const TrackerConfig& config, const TrackerConfig& fit,
                int threads);
  ~SearchWorkers();

  // Each start fitted from where it is (reference::PoseRefiner::refine), in order.
  std::vector<Pose> fit(std::span<const Pose> starts, const DepthImage& working, std::span<const double> occlusion);
  // Each pose's silhouette shares, in order (silhouette_shares with the tracker's loss band).
  std::vector<SilhouetteShares> shares(std::span<const Pose> poses, const DepthImage& working);
  // Calls item(i) for i in [0, n), split over the threads; item must only write its own outputs.
  void each(size_t n, const std::function<void(size_t)>& item);

 private:
  // One thread's refiner and rasterizer, made when a thread first needs them.
  struct Kit;
  Kit& kit(int thread);
  // The pool for n items, made on first use; null where they run on the caller's thread alone.
  ThreadPool* pool(size_t n);
  // Calls task(i, kit) for i in [0, n) on the threads, each with its thread's kit.
  void run_with_kits(size_t n, const std::function<void(size_t, Kit&)>& task);

  const Mesh mesh_;
  Camera working_;
  TrackerConfig config_, fit_;
  int threads_;
  std::unique_ptr<ThreadPool> pool_;  // made by the first call that splits (threads_ > 1)
  std::vector<std::unique_ptr<Kit>> kits_;
};

}  // namespace depthtrack
