#include "compute/cuda/cuda_launch_graph.hpp"

#include <algorithm>
#include <cstring>
#include <depthtrack/error.hpp>

#include "compute/cuda/cuda_kernel.hpp"

namespace depthtrack::compute::cuda {

namespace {
// Distinct launch sequences kept instantiated: a frame has two or three (the first frame's has no
// propagation, a rare one retires old time indices), each handed over in two parts (Queue::flush_batch)
// and kept for either parity of the swapped buffers, and a queue's other batches a few more.
constexpr size_t kMaxGraphs = 16;

bool same_shape(const LaunchShape& a, const LaunchShape& b) {
  return std::equal(a.grid, a.grid + 3, b.grid) && std::equal(a.block, a.block + 3, b.block);
}
}  // namespace

struct LaunchGraphs::Graph {
  const DriverApi* api = nullptr;
  CUgraph graph = nullptr;
  CUgraphExec exec = nullptr;
  struct Node {
    CUfunction function = nullptr;
    LaunchShape shape;
    bool timed = false;
    size_t event_slot = 0;  // the events its event-record nodes record (timed only)
    CUgraphNode node = nullptr;
    std::vector<unsigned char> bytes;  // the arguments the executable graph holds now
  };
  std::vector<Node> nodes;

  ~Graph() {
    // An executable graph still running is freed by the driver when it completes.
    if (exec) api->cuGraphExecDestroy(exec);
    if (graph) api->cuGraphDestroy(graph);
  }
};

bool LaunchGraphs::supported(const DriverApi& api) {
  return api.cuGraphCreate && api.cuGraphDestroy && api.cuGraphAddKernelNode && api.cuGraphAddEventRecordNode &&
         api.cuGraphInstantiate && api.cuGraphExecDestroy && api.cuGraphExecKernelNodeSetParams && api.cuGraphLaunch;
}

LaunchGraphs::LaunchGraphs(std::shared_ptr<const Context> context) : context_(std::move(context)) {}

LaunchGraphs::~LaunchGraphs() {
  if (!context_->try_make_current()) {
    for (auto& graph : graphs_) (void)graph.release();  // the context is gone, and its graphs with it
    return;
  }
  graphs_.clear();
}

EventPtr LaunchGraphs::record(const CudaKernel& kernel, const LaunchShape& shape, bool timed) {
  if (launches_.size() <= recorded_) launches_.resize(recorded_ + 1);
  Launch& launch = launches_[recorded_];
  launch.bytes.clear();
  launch.offsets.clear();
  kernel.copy_arguments(launch.bytes, launch.offsets);  // throws for an argument never set
  launch.function = kernel.function();
  launch.name = &kernel.name();
  launch.shape = shape;
  launch.timed = timed;
  ++recorded_;
  if (!timed) return nullptr;
  const size_t slot = launch.event_slot = next_event_slot_++;
  if (events_.size() <= slot) events_.resize(slot + 1);
  if (!events_[slot]) events_[slot] = std::make_shared<CudaEvent>(context_);
  return events_[slot];
}

void LaunchGraphs::check(CUresult status, const char* call, const Launch& launch) const {
  if (status == CUDA_SUCCESS) return;
  const std::string text = std::string(call) + " for kernel '" + *launch.name + "'";
  context_->check(status, text.c_str());
}

bool LaunchGraphs::matches(const Graph& graph) const {
  if (graph.nodes.size() != recorded_) return false;
  for (size_t i = 0; i < recorded_; ++i) {
    const Launch& l = launches_[i];
    const Graph::Node& n = graph.nodes[i];
    if (l.function != n.function || l.timed != n.timed || !same_shape(l.shape, n.shape)) return false;
    if (l.timed && l.event_slot != n.event_slot) return false;  // its nodes record other events
  }
  return true;
}

namespace {
CUDA_KERNEL_NODE_PARAMS node_params(CUfunction function, const LaunchShape& shape, std::vector<void*>& pointers) {
  CUDA_KERNEL_NODE_PARAMS params;
  std::memset(&params, 0, sizeof params);  // ctx null: the current context
  params.func = function;
  params.gridDimX = shape.grid[0];
  params.gridDimY = shape.grid[1];
  params.gridDimZ = shape.grid[2];
  params.blockDimX = shape.block[0];
  params.blockDimY = shape.block[1];
  params.blockDimZ = shape.block[2];
  params.sharedMemBytes = 0;  // kernels declare fixed-size __local arrays
  params.kernelParams = pointers.data();
  return params;
}

std::vector<void*>& pointers_into(std::vector<unsigned char>& bytes, const std::vector<size_t>& offsets,
                                  std::vector<void*>& pointers) {
  pointers.clear();
  for (const size_t offset : offsets) pointers.push_back(bytes.data() + offset);
  return pointers;
}
}  // namespace

std::unique_ptr<LaunchGraphs::Graph> LaunchGraphs::build() {
  const DriverApi& api = context_->api();
  auto graph = std::make_unique<Graph>();
  graph->api = &api;
  context_->check(api.cuGraphCreate(&graph->graph, 0), "cuGraphCreate");
  CUgraphNode previous = nullptr;
  const auto after = [&](CUgraphNode node) { previous = node; };
  std::vector<void*> pointers;
  for (size_t i = 0; i < recorded_; ++i) {
    Launch& launch = launches_[i];
    const size_t dependencies = previous ? 1 : 0;
    if (launch.timed) {
      CUgraphNode start = nullptr;
      check(api.cuGraphAddEventRecordNode(&start, graph->graph, &previous, dependencies,
                                          events_[launch.event_slot]->start_handle()),
            "cuGraphAddEventRecordNode", launch);
      after(start);
    }
    Graph::Node node;
    node.function = launch.function;
    node.shape = launch.shape;
    node.timed = launch.timed;
    node.event_slot = launch.event_slot;
    node.bytes = launch.bytes;
    const CUDA_KERNEL_NODE_PARAMS params =
        node_params(launch.function, launch.shape, pointers_into(launch.bytes, launch.offsets, pointers));
    check(api.cuGraphAddKernelNode(&node.node, graph->graph, &previous, previous ? 1 : 0, &params),
          "cuGraphAddKernelNode", launch);
    after(node.node);
    if (launch.timed) {
      CUgraphNode end = nullptr;
      check(api.cuGraphAddEventRecordNode(&end, graph->graph, &previous, 1, events_[launch.event_slot]->end_handle()),
            "cuGraphAddEventRecordNode", launch);
      after(end);
    }
    graph->nodes.push_back(std::move(node));
  }
  context_->check(api.cuGraphInstantiate(&graph->exec, graph->graph, 0), "cuGraphInstantiate");
  ++graphs_built_;
  return graph;
}

// Sets each node whose recorded arguments differ from what the executable graph holds.
void LaunchGraphs::update(Graph& graph) {
  const DriverApi& api = context_->api();
  std::vector<void*> pointers;
  for (size_t i = 0; i < recorded_; ++i) {
    Launch& launch = launches_[i];
    Graph::Node& node = graph.nodes[i];
    if (launch.bytes == node.bytes) continue;
    const CUDA_KERNEL_NODE_PARAMS params =
        node_params(launch.function, launch.shape, pointers_into(launch.bytes, launch.offsets, pointers));
    check(api.cuGraphExecKernelNodeSetParams(graph.exec, node.node, &params), "cuGraphExecKernelNodeSetParams", launch);
    node.bytes = launch.bytes;
    ++nodes_updated_;
  }
}

// Of the graphs with the same launches, the one holding the most of the recorded arguments: a frame
// that swaps double buffers alternates between two sets of pointers, so each set keeps a graph of its
// own and a replay sets only what really changed (a time, a frame index), not every swapped pointer.
size_t LaunchGraphs::differing_nodes(const Graph& graph) const {
  size_t differing = 0;
  for (size_t i = 0; i < recorded_; ++i) differing += launches_[i].bytes != graph.nodes[i].bytes;
  return differing;
}

LaunchGraphs::Graph& LaunchGraphs::graph_for_recorded() {
  auto found = graphs_.end();
  size_t fewest = 0;
  for (auto g = graphs_.begin(); g != graphs_.end(); ++g) {
    if (!matches(**g)) continue;
    const size_t differing = differing_nodes(**g);
    if (found == graphs_.end() || differing < fewest) found = g, fewest = differing;
  }
  // A second graph of the same launches is built while the best one still differs in half its nodes
  // and there is room for it (the first frame's graph of each buffer parity).
  if (found != graphs_.end() && 2 * fewest > recorded_ && graphs_.size() < kMaxGraphs) found = graphs_.end();
  if (found != graphs_.end()) {
    std::rotate(found, found + 1, graphs_.end());  // now the most recently used
    update(*graphs_.back());
    return *graphs_.back();
  }
  std::unique_ptr<Graph> built = build();
  if (graphs_.size() >= kMaxGraphs) graphs_.erase(graphs_.begin());
  graphs_.push_back(std::move(built));
  return *graphs_.back();
}

void LaunchGraphs::submit(CUstream stream) {
  if (recorded_ == 0) return;
  context_->make_current();
  // Whatever happens, this batch's launches are spent: a failed graph must not be retried with them.
  struct Spent {
    size_t& recorded;
    ~Spent() { recorded = 0; }
  } spent{recorded_};
  Graph& graph = graph_for_recorded();
  context_->check(context_->api().cuGraphLaunch(graph.exec, stream), "cuGraphLaunch");
}

}  // namespace depthtrack::compute::cuda
