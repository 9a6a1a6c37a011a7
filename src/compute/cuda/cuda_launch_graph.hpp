#pragma once
// A queue's batched launches (Queue::begin_batch .. end_batch) as CUDA graphs. A batch's launches are
// recorded (kernel, shape, a copy of the arguments, timed or not); at submit they become a chain of
// kernel nodes, each timed one between two event-record nodes, instantiated once and replayed whenever a
// later batch launches the same kernels over the same shapes. Only the nodes whose arguments changed are
// set again (cuGraphExecKernelNodeSetParams). A frame's launches then cost the host one cuGraphLaunch
// and the device no gaps between launches.
#include <cstdint>
#include <memory>
#include <vector>

#include "compute/cuda/cuda_event.hpp"
#include "compute/cuda/cuda_launch.hpp"

namespace depthtrack::compute::cuda {

class CudaKernel;

class LaunchGraphs {
 public:
  explicit LaunchGraphs(std::shared_ptr<const Context> context);
  ~LaunchGraphs();
  LaunchGraphs(const LaunchGraphs&) = delete;
  LaunchGraphs& operator=(const LaunchGraphs&) = delete;

  // Whether the driver has every graph function this needs.
  static bool supported(const DriverApi& api);

  // A batch begins: its timed launches take event slots from the first again.
  void begin_batch() { next_event_slot_ = 0; }
  // Records a launch of `kernel` with its arguments as set now. A timed launch's event is the same
  // object at the same place of every batch (the replayed graph records it), so it is valid until the
  // batch's next part is submitted after the next begin_batch. The parts of one batch (submitted in
  // turn: Queue::flush_batch) take different slots.
  EventPtr record(const CudaKernel& kernel, const LaunchShape& shape, bool timed);
  bool empty() const { return recorded_ == 0; }
  // Launches what was recorded since the last submit on `stream` (nothing when nothing was).
  void submit(CUstream stream);
  // Graphs instantiated so far (a replay builds none), and kernel nodes whose arguments a replay set.
  uint64_t graphs_built() const { return graphs_built_; }
  uint64_t nodes_updated() const { return nodes_updated_; }

 private:
  struct Launch {
    CUfunction function = nullptr;
    const std::string* name = nullptr;  // the kernel's, for messages while this batch lasts
    LaunchShape shape;
    bool timed = false;
    size_t event_slot = 0;             // a timed launch's place in events_
    std::vector<unsigned char> bytes;  // the arguments' values
    std::vector<size_t> offsets;       // where each argument starts in bytes
  };
  struct Graph;

  // The cached graph for the recorded launches, or a new one built for them.
  Graph& graph_for_recorded();
  bool matches(const Graph& graph) const;
  size_t differing_nodes(const Graph& graph) const;
  std::unique_ptr<Graph> build();
  void update(Graph& graph);
  void check(CUresult status, const char* call, const Launch& launch) const;

  std::shared_ptr<const Context> context_;
  std::vector<Launch> launches_;  // reused from batch to batch: the first recorded_ are this batch's
  size_t recorded_ = 0;
  std::vector<std::shared_ptr<CudaEvent>> events_;  // by slot, made when first timed
  size_t next_event_slot_ = 0;                      // the batch's next timed launch's slot
  std::vector<std::unique_ptr<Graph>> graphs_;      // the most recently used last
  uint64_t graphs_built_ = 0, nodes_updated_ = 0;
};

}  // namespace depthtrack::compute::cuda
