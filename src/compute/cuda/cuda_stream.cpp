#include "compute/cuda/cuda_stream.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>

#include "compute/cuda/cuda_context.hpp"

namespace depthtrack::compute::cuda {

namespace {
bool priorities_turned_off() {
  const char* value = std::getenv("DEPTHTRACK_CUDA_STREAM_PRIORITIES");
  return value && (std::strcmp(value, "0") == 0 || std::strcmp(value, "off") == 0);
}
}  // namespace

int ranked_stream_priority(unsigned rank, int least, int greatest) {
  if (greatest >= least) return least;  // one level only (or a range the other way round: none)
  return static_cast<int>(std::min<long long>(static_cast<long long>(greatest) + rank, least));
}

CUstream create_ranked_stream(const Context& context, unsigned rank) {
  const DriverApi& api = context.api();
  CUstream stream = nullptr;
  int least = 0, greatest = 0;
  if (!priorities_turned_off() && api.cuStreamCreateWithPriority && api.cuCtxGetStreamPriorityRange &&
      api.cuCtxGetStreamPriorityRange(&least, &greatest) == CUDA_SUCCESS && greatest < least) {
    context.check(
        api.cuStreamCreateWithPriority(&stream, CU_STREAM_DEFAULT, ranked_stream_priority(rank, least, greatest)),
        "cuStreamCreateWithPriority");
    return stream;
  }
  context.check(api.cuStreamCreate(&stream, CU_STREAM_DEFAULT), "cuStreamCreate");
  return stream;
}

}  // namespace depthtrack::compute::cuda
