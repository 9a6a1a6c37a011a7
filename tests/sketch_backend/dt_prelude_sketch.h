/* dt_prelude_sketch.h: the sketch backend's kernel-language words (none: it compiles nothing). A real backend
 * maps OpenCL C's words here, as src/compute/cuda/dt_prelude_cuda.h does. */
#define DT_DEVICE_PRELUDE 1
