#include "compute/cuda/cuda_launch.hpp"

#include <depthtrack/error.hpp>

namespace depthtrack::compute::cuda {
namespace {

std::string sizes(const size_t (&values)[3], unsigned dimensions) {
  std::string out;
  for (unsigned d = 0; d < dimensions; ++d) out += (d ? " x " : "") + std::to_string(values[d]);
  return out;
}

}  // namespace

LaunchShape launch_shape(const NdRange& range, const LaunchLimits& limits, const std::string& kernel,
                         const std::string& where) {
  // The texts are made only for an error: a frame launches some 30 kernels.
  const auto launch = [&] { return "launch of kernel '" + kernel + "' on " + where; };
  if (range.dimensions < 1 || range.dimensions > 3)
    throw InputError(launch() + ": an nd-range has 1 to 3 dimensions, not " + std::to_string(range.dimensions));
  const auto shape = [&] {
    return " (global " + sizes(range.global, range.dimensions) + ", local " + sizes(range.local, range.dimensions) +
           ")";
  };
  LaunchShape out;
  size_t threads = 1;
  for (unsigned d = 0; d < range.dimensions; ++d) {
    const size_t global = range.global[d], local = range.local[d];
    const auto axis = [d] { return " in dimension " + std::to_string(d); };
    if (global == 0 || local == 0) throw InputError(launch() + ": zero work-items" + axis() + shape());
    if (global % local != 0)
      throw InputError(launch() + ": global size " + std::to_string(global) + " is not a multiple of local size " +
                       std::to_string(local) + axis() + shape());
    if (local > limits.max_block[d])
      throw BackendError(launch() + ": local size " + std::to_string(local) + axis() + " exceeds the device's " +
                         std::to_string(limits.max_block[d]) + shape());
    if (global / local > limits.max_grid[d])
      throw BackendError(launch() + ": " + std::to_string(global / local) + " work-groups" + axis() +
                         " exceed the device's " + std::to_string(limits.max_grid[d]) + shape());
    out.grid[d] = static_cast<unsigned>(global / local);
    out.block[d] = static_cast<unsigned>(local);
    threads *= local;
  }
  if (threads > limits.max_threads)
    throw BackendError(launch() + ": a work-group of " + std::to_string(threads) + " work-items exceeds the " +
                       std::to_string(limits.max_threads) + " this kernel can run per block" + shape());
  return out;
}

}  // namespace depthtrack::compute::cuda
