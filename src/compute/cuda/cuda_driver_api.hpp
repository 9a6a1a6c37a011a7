#pragma once
// The CUDA driver API as a table of function pointers, filled from libcuda.so.1 at run time
// (dlopen), so that libdepthtrack loads and runs where no NVIDIA driver is installed.
//
// Each entry is declared with the type of cuda.h's own prototype and resolved under the name
// cuda.h maps it to (cuMemAlloc -> cuMemAlloc_v2, cuEventElapsedTime -> cuEventElapsedTime_v2),
// so the pointer's signature always matches the symbol it was loaded from. Call sites read like
// ordinary driver code: api.cuMemAlloc(&pointer, bytes).
#include <cuda.h>

#include <string>

namespace depthtrack::compute::cuda {

// Every driver function the backend uses. X(f): required; the driver is unusable without it.
// clang-format off
#define DT_CUDA_DRIVER_FUNCTIONS(X)                                                                    \
  X(cuInit) X(cuDriverGetVersion) X(cuGetErrorName) X(cuGetErrorString)                                \
  X(cuDeviceGetCount) X(cuDeviceGet) X(cuDeviceGetName) X(cuDeviceGetAttribute) X(cuDeviceTotalMem)    \
  X(cuDevicePrimaryCtxRetain) X(cuDevicePrimaryCtxRelease) X(cuCtxSetCurrent)                          \
  X(cuMemGetInfo) X(cuMemAlloc) X(cuMemFree) X(cuMemAllocHost) X(cuMemFreeHost)                       \
  X(cuMemcpyHtoDAsync) X(cuMemcpyDtoHAsync) X(cuMemcpyDtoDAsync)                                       \
  X(cuStreamCreate) X(cuStreamDestroy) X(cuStreamSynchronize)                                          \
  X(cuEventCreate) X(cuEventDestroy) X(cuEventRecord) X(cuEventSynchronize) X(cuEventElapsedTime)      \
  X(cuModuleLoadDataEx) X(cuModuleUnload) X(cuModuleGetFunction) X(cuFuncGetAttribute) X(cuLaunchKernel)
// clang-format on

// Functions the backend uses when the driver has them (cuFuncGetParamInfo: CUDA 12.4+), and those
// of graphics interop, exportable memory, graphs (cuGraphAddKernelNode_v2: CUDA 12.0+) and stream
// priorities, which a driver may lack.
// clang-format off
#define DT_CUDA_DRIVER_OPTIONAL_FUNCTIONS(X)                                                           \
  X(cuFuncGetParamInfo) X(cuDeviceGetUuid)                                                             \
  X(cuGraphicsMapResources) X(cuGraphicsUnmapResources) X(cuGraphicsUnregisterResource)                \
  X(cuGraphicsSubResourceGetMappedArray) X(cuGraphicsResourceGetMappedPointer) X(cuMemcpy2DAsync)          \
  X(cuMemGetAllocationGranularity) X(cuMemCreate) X(cuMemExportToShareableHandle) X(cuMemRelease)          \
  X(cuGraphCreate) X(cuGraphDestroy) X(cuGraphAddKernelNode) X(cuGraphAddEventRecordNode)              \
  X(cuGraphInstantiate) X(cuGraphExecDestroy) X(cuGraphExecKernelNodeSetParams) X(cuGraphLaunch)          \
  X(cuStreamCreateWithPriority) X(cuCtxGetStreamPriorityRange) X(cuStreamGetPriority)
// clang-format on

struct DriverApi {
#define DT_CUDA_DECLARE(f) decltype(&::f) f = nullptr;
  DT_CUDA_DRIVER_FUNCTIONS(DT_CUDA_DECLARE)
  DT_CUDA_DRIVER_OPTIONAL_FUNCTIONS(DT_CUDA_DECLARE)
#undef DT_CUDA_DECLARE
};

// The table, loaded and cuInit(0)-ed once (thread-safe); nullptr when the driver is absent or
// unusable, and then driver_failure() says why.
const DriverApi* driver_api();
const std::string& driver_failure();
// The table, or BackendError "CUDA is unavailable: <why>".
const DriverApi& require_driver();
// Any other symbol of the loaded driver, by its exact name (the GL interop entry points, whose
// header cudaGL.h would bring in a second set of GL declarations); null when absent.
void* driver_symbol(const char* name);

}  // namespace depthtrack::compute::cuda
