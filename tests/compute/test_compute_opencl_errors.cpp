// OpenCL status codes become their symbolic names in every BackendError (no device needed).
#include <catch2/catch.hpp>
#include <depthtrack/error.hpp>
#include <string>

#include "compute/opencl/cl_errors.hpp"

using namespace depthtrack;
using compute::opencl::error_name;

TEST_CASE("OpenCL error codes have their symbolic names", "[compute]") {
  CHECK(std::string(error_name(-5)) == "CL_OUT_OF_RESOURCES");
  CHECK(std::string(error_name(-61)) == "CL_INVALID_BUFFER_SIZE");
  CHECK(std::string(error_name(-72)) == "CL_MAX_SIZE_RESTRICTION_EXCEEDED");  // 3.0, beyond the 1.2 headers
  CHECK(std::string(error_name(-1001)) == "CL_PLATFORM_NOT_FOUND_KHR");
  CHECK(std::string(error_name(-12345)) == "unknown OpenCL error");
  // Every code from -1 to -19 and -30 to -72 is named.
  for (int code = -1; code >= -72; --code)
    if (code > -20 || code < -29) CHECK(std::string(error_name(code)).rfind("CL_", 0) == 0);
}

TEST_CASE("check() throws a BackendError naming the call, the error and the device", "[compute]") {
  CHECK_NOTHROW(compute::opencl::check(0, "clFinish", "dev"));
  try {
    compute::opencl::check(-61, "clCreateBuffer", "Some Device");
    FAIL("no error thrown");
  } catch (const BackendError& e) {
    CHECK(std::string(e.what()) == "clCreateBuffer failed: CL_INVALID_BUFFER_SIZE (-61) on Some Device");
  }
}
