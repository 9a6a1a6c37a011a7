#pragma once
// The streams of a context's queues, at priorities in the order the queues were made. Several
// filters on one device (MultiTracker: a filter, and a queue, per object) each run a chain of small
// launches (the fit's draws and sums, the summary, the resampling) beside the others' render_weigh,
// whose thousands of groups fill the device. At equal priority a chain's next launch waits for free
// room behind the groups already queued; with the first-made stream the most urgent, the block
// scheduler runs the first object's chain ahead of the later objects' groups, so the objects' frames
// finish one after another rather than all at the end. Measured (H100, three
// ycbv-0000 objects at 2,000 particles over one, mutual occlusion off / on): 1.99x / 2.81x at one
// priority, 1.86x / 2.47x ranked. Graphs launched into a stream take its priority.
// DEPTHTRACK_CUDA_STREAM_PRIORITIES=0 or off (read when a queue is made): every stream at the default
// priority, for comparison (scripts/gpu/small-frame.sh times both).
#include <cuda.h>

namespace depthtrack::compute::cuda {

class Context;

// The priority of the rank-th queue made in a context (0: the first) within the driver's range
// [greatest, least] (cuCtxGetStreamPriorityRange; lower is more urgent): greatest + rank, at most least.
int ranked_stream_priority(unsigned rank, int least, int greatest);

// A blocking stream (it orders against the legacy default stream, as interop needs) for the
// rank-th queue of `context`: at ranked_stream_priority where the driver has stream priorities and
// they are not turned off, else at the default priority.
CUstream create_ranked_stream(const Context& context, unsigned rank);

}  // namespace depthtrack::compute::cuda
