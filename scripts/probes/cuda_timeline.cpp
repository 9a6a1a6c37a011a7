// A CUDA timeline without Nsight Systems (the GPU machine has none): a CUPTI injection library that
// records every kernel, copy and driver call with its start and end on CUPTI's one clock, and writes them
// as CSV when the process exits. Not part of the build; made by hand and used by scripts/gpu/tile-variants.sh:
//   g++ -O2 -shared -fPIC -I$CUDA/include scripts/probes/cuda_timeline.cpp -o libtimeline.so -L$CUDA/lib -lcupti \
//     -Wl,-rpath,'$ORIGIN' && cp $CUDA/lib/libcupti.so.13 .   (the GPU machine has no CUPTI of its own)
//   CUDA_INJECTION64_PATH=$PWD/libtimeline.so DT_TIMELINE_OUT=timeline.csv ./depthtrack_bench ...
// Rows: kind,name,stream,start_ns,end_ns,detail (grid x block for kernels, bytes for copies, the calling
// thread for driver calls). CONCURRENT_KERNEL keeps kernels concurrent (the plain KERNEL kind serializes).
#include <cupti.h>

#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <string>

namespace {

constexpr size_t kBufferBytes = 8u << 20;
FILE* out = nullptr;
std::mutex out_mutex;

void check(CUptiResult result, const char* call) {
  if (result == CUPTI_SUCCESS) return;
  const char* text = nullptr;
  cuptiGetResultString(result, &text);
  std::fprintf(stderr, "cuda_timeline: %s failed: %s\n", call, text ? text : "?");
  std::exit(1);
}

void CUPTIAPI buffer_requested(uint8_t** buffer, size_t* size, size_t* max_records) {
  *buffer = static_cast<uint8_t*>(std::aligned_alloc(8, kBufferBytes));
  *size = kBufferBytes;
  *max_records = 0;
}

void write_record(const CUpti_Activity* record) {
  switch (record->kind) {
    case CUPTI_ACTIVITY_KIND_CONCURRENT_KERNEL: {
      const auto* k = reinterpret_cast<const CUpti_ActivityKernel10*>(record);
      std::fprintf(out, "kernel,%s,%u,%llu,%llu,%dx%d\n", k->name, k->streamId,
                   static_cast<unsigned long long>(k->start), static_cast<unsigned long long>(k->end), k->gridX,
                   k->blockX);
      break;
    }
    case CUPTI_ACTIVITY_KIND_MEMCPY: {
      const auto* m = reinterpret_cast<const CUpti_ActivityMemcpy6*>(record);
      std::fprintf(out, "copy,%s,%u,%llu,%llu,%llu\n", m->copyKind == CUPTI_ACTIVITY_MEMCPY_KIND_HTOD ? "HtoD" : "DtoH",
                   m->streamId, static_cast<unsigned long long>(m->start), static_cast<unsigned long long>(m->end),
                   static_cast<unsigned long long>(m->bytes));
      break;
    }
    case CUPTI_ACTIVITY_KIND_DRIVER: {
      const auto* a = reinterpret_cast<const CUpti_ActivityAPI*>(record);
      const char* name = nullptr;
      cuptiGetCallbackName(CUPTI_CB_DOMAIN_DRIVER_API, a->cbid, &name);
      std::fprintf(out, "driver,%s,,%llu,%llu,%u\n", name ? name : "?", static_cast<unsigned long long>(a->start),
                   static_cast<unsigned long long>(a->end), a->threadId);
      break;
    }
    default:
      break;
  }
}

void CUPTIAPI buffer_completed(CUcontext, uint32_t, uint8_t* buffer, size_t, size_t valid) {
  {
    const std::lock_guard<std::mutex> lock(out_mutex);
    CUpti_Activity* record = nullptr;
    while (cuptiActivityGetNextRecord(buffer, valid, &record) == CUPTI_SUCCESS) write_record(record);
  }
  std::free(buffer);
}

void flush_at_exit() {
  cuptiActivityFlushAll(1);
  if (out) std::fclose(out);
}

}  // namespace

extern "C" int InitializeInjection() {
  const char* path = std::getenv("DT_TIMELINE_OUT");
  out = std::fopen(path ? path : "timeline.csv", "w");
  if (!out) {
    std::perror("cuda_timeline: DT_TIMELINE_OUT");
    return 0;
  }
  std::fprintf(out, "kind,name,stream,start_ns,end_ns,detail\n");
  check(cuptiActivityRegisterCallbacks(buffer_requested, buffer_completed), "cuptiActivityRegisterCallbacks");
  check(cuptiActivityEnable(CUPTI_ACTIVITY_KIND_CONCURRENT_KERNEL), "cuptiActivityEnable(CONCURRENT_KERNEL)");
  check(cuptiActivityEnable(CUPTI_ACTIVITY_KIND_MEMCPY), "cuptiActivityEnable(MEMCPY)");
  check(cuptiActivityEnable(CUPTI_ACTIVITY_KIND_DRIVER), "cuptiActivityEnable(DRIVER)");
  std::atexit(flush_at_exit);
  return 1;
}
