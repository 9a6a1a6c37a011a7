#pragma once
// A kernel's launch from a struct of its arguments, each set by name: every kernel has one such struct
// (the filter's in src/filter/kernels/, the atlas rasterizer's in src/atlas/rasterize_args.hpp), its fields
// in the kernel's parameter order (cl/*.cl), and in_order() hands them to the compute layer in that order.
// A call site names what it passes:
//   kernels::launch(where, kernels::PropagateArgs{.state = state, .count = n, ...});
#include <tuple>

#include "compute/buffer.hpp"
#include "compute/queue.hpp"

namespace depthtrack::kernels {

template <class T>
using Buf = const compute::Buffer<T>&;  // a kernel's buffer argument (read or written: the field's comment)

// Where a launch goes: the queue, the kernel, its nd-range, and whether its device time is read
// (untimed: no event, null; compute::launch_timed_if).
struct Launch {
  compute::Queue& queue;
  compute::Kernel& kernel;
  compute::NdRange range;
  bool timed = true;
};

template <class Args>
compute::EventPtr launch(const Launch& where, const Args& args) {
  return std::apply(
      [&](const auto&... a) {
        return compute::launch_timed_if(where.timed, where.queue, where.kernel, where.range, a...);
      },
      args.in_order());
}

// Sets the kernel's arguments without launching it, for a run of launches of the same arguments.
template <class Args>
void set_args(compute::Kernel& kernel, const Args& args) {
  std::apply([&](const auto&... a) { compute::set_launch_args(kernel, a...); }, args.in_order());
}

}  // namespace depthtrack::kernels
