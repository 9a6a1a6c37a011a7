#pragma once
// OpenCL status codes as the names programmers search for, and the one way this backend fails.
// Plain int for cl_int (both are 32-bit), so this header needs no OpenCL header.
#include <string>

namespace depthtrack::compute::opencl {

// "CL_OUT_OF_RESOURCES" for -5; "unknown OpenCL error" for a code no header defines.
const char* error_name(int code);

// "clCreateBuffer failed: CL_INVALID_BUFFER_SIZE (-61) on <device>[: <context>]".
std::string failure_message(int status, const char* call, const std::string& device, const std::string& context = {});

// Throws BackendError with failure_message() unless status is CL_SUCCESS (0).
void check(int status, const char* call, const std::string& device = {}, const std::string& context = {});

}  // namespace depthtrack::compute::opencl
