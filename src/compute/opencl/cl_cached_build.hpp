#pragma once
// Program builds through the on-disk binary cache (compute/program_binary_cache.hpp): a program this
// device built before is created from its stored binary (clCreateProgramWithBinary), which on PoCL
// skips the preprocessing and hashing of the source that its own cache still does on every build.
#include <optional>
#include <string>
#include <vector>

#include "compute/device_info.hpp"
#include "compute/opencl/cl_program.hpp"
#include "compute/program_binary_cache.hpp"

namespace depthtrack::compute::opencl {

// Everything a stored binary depends on: the device and driver, the build options and the source.
std::string binary_cache_key(const DeviceInfo& device, const std::string& options, const std::string& source);

// From the cache when it holds a binary that the driver accepts; otherwise built from source (a
// failed build throws as build_program does) and stored, replacing an entry the driver refused.
// Without a cache, exactly build_program.
std::unique_ptr<ClProgram> build_cached(const std::optional<ProgramBinaryCache>& cache, cl_context context,
                                        cl_device_id device, const DeviceInfo& info, const std::string& name,
                                        const std::string& source, const std::vector<std::string>& definitions);

}  // namespace depthtrack::compute::opencl
