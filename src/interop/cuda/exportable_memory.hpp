#pragma once
// Device memory that other APIs can import: allocated by CUDA's virtual memory management with a
// POSIX fd handle. GL (GL_EXT_memory_object_fd) and OpenCL (cl_khr_external_memory_opaque_fd) can
// only import, so on NVIDIA this is the allocator that lets the two share the atlas.
#include <array>
#include <cuda.h>
#include <memory>
#include <optional>
#include <string>

#include "compute/cuda/cuda_context.hpp"

namespace depthtrack::interop {

class ExportableMemory {
 public:
  // At least `bytes` on the CUDA device with this UUID; null, with the reason in why_not, when
  // there is no such device or the driver cannot export.
  static std::unique_ptr<ExportableMemory> make(const std::optional<std::array<unsigned char, 16>>& uuid,
                                                size_t bytes, std::string& why_not);
  ~ExportableMemory();
  ExportableMemory(const ExportableMemory&) = delete;
  ExportableMemory& operator=(const ExportableMemory&) = delete;

  size_t bytes() const { return bytes_; }
  // A new fd for the allocation; the caller gives it to one importer (or closes it).
  int export_fd() const;

 private:
  ExportableMemory(std::shared_ptr<const compute::cuda::Context> context, CUmemGenericAllocationHandle handle,
                   size_t bytes);
  std::shared_ptr<const compute::cuda::Context> context_;
  CUmemGenericAllocationHandle handle_;
  size_t bytes_;
};

}  // namespace depthtrack::interop
