#pragma once
// CUDA programs through the on-disk binary cache (compute/program_binary_cache.hpp): NVRTC's cubin
// (or PTX) for a program this device built before is loaded as it is, without NVRTC compiling it.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "compute/cuda/cuda_context.hpp"
#include "compute/cuda/cuda_module.hpp"
#include "compute/program_binary_cache.hpp"

namespace depthtrack::compute::cuda {

// Everything a stored image depends on: the device, driver and architecture, NVRTC's version, the
// definitions and the source.
std::string binary_cache_key(const DeviceInfo& device, const std::vector<std::string>& definitions,
                             const std::string& source);

// From the cache when it holds an image the driver loads; otherwise compiled (a failed compile throws
// as compile_for_device does) and stored, replacing an entry the driver refused. Without a cache,
// exactly a compile.
std::unique_ptr<CudaProgram> build_cached(const std::optional<ProgramBinaryCache>& cache,
                                          const std::shared_ptr<const Context>& context, const std::string& name,
                                          const std::string& source, const std::vector<std::string>& definitions);

}  // namespace depthtrack::compute::cuda
