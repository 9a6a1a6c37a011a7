#include "compute/cuda/cuda_stream.hpp"

#include <algorithm>

#include "compute/cuda/cuda_context.hpp"
#include "compute/environment_switch.hpp"

namespace depthtrack::compute::cuda {

int ranked_stream_priority(unsigned rank, int least, int greatest) {
  if (greatest >= least) return least;  // one level only (or a range the other way round: none)
  return static_cast<int>(std::min<long long>(static_cast<long long>(greatest) + rank, least));
}

CUstream create_ranked_stream(const Context& context, unsigned rank) {
  const DriverApi& api = context.api();
  CUstream stream = nullptr;
  int least = 0, greatest = 0;
  const bool ranked = !turned_off_by_environment("DEPTHTRACK_CUDA_STREAM_PRIORITIES") &&
                      api.cuStreamCreateWithPriority && api.cuCtxGetStreamPriorityRange &&
                      api.cuCtxGetStreamPriorityRange(&least, &greatest) == CUDA_SUCCESS;
  if (ranked) {  // a one-level range gives every rank the default (ranked_stream_priority)
    context.check(
        api.cuStreamCreateWithPriority(&stream, CU_STREAM_DEFAULT, ranked_stream_priority(rank, least, greatest)),
        "cuStreamCreateWithPriority");
    return stream;
  }
  context.check(api.cuStreamCreate(&stream, CU_STREAM_DEFAULT), "cuStreamCreate");
  return stream;
}

}  // namespace depthtrack::compute::cuda
