#pragma once
// Programs built from OpenCL C source at run time, and their kernels.
#include <memory>
#include <string>
#include <vector>

#include "compute/opencl/cl_handle.hpp"
#include "compute/queue.hpp"

namespace depthtrack::compute::opencl {

class ClProgram final : public Program {
 public:
  ClProgram(ProgramHandle program, std::string name, std::string device, bool from_binary = false)
      : program_(std::move(program)), name_(std::move(name)), device_(std::move(device)), from_binary_(from_binary) {}
  std::unique_ptr<Kernel> kernel(const std::string& name) override;
  bool loaded_from_disk() const override { return from_binary_; }
  cl_program get() const { return program_.get(); }

 private:
  ProgramHandle program_;
  std::string name_;
  std::string device_;
  bool from_binary_;
};

// OpenCL C's words (dt_prelude_opencl.h), put before every program's source; the binary cache keys on it.
const std::string& opencl_prelude();

// "-cl-std=CL1.2 -D <definition>..."; InputError for a definition with a blank or quote in it.
std::string build_options(const std::vector<std::string>& definitions);

// Builds source for one device with "-cl-std=CL1.2 -D <definition>...". A failed build throws
// BackendError with the device, the options, the build log and the numbered source around the error.
std::unique_ptr<ClProgram> build_program(cl_context context, cl_device_id device, const std::string& device_name,
                                         const std::string& name, const std::string& source,
                                         const std::vector<std::string>& definitions);

}  // namespace depthtrack::compute::opencl
