/* Per-pixel-time occlusion stores, per particle and pixel, not the time a pixel was last seen but the
 * 16-bit index of that frame in a table of frame times (one float per frame, written by weigh): half
 * the bytes of a float time, and the same float `now - time` as before. Frames take indices
 * 0 .. DT_TIME_CYCLE - 1 in turn; DT_TIME_NEVER stands for time 0 (the start: what initialize fills in).
 * An index comes round again after DT_TIME_CYCLE frames, so every DT_TIME_RETIRE_EVERY frames the
 * pixels last seen DT_TIME_RETIRE_AGE frames ago or more are set to DT_TIME_NEVER (time_index.cl):
 * their occlusion is then aged from time 0. That is the same float as from their own time once
 * c^age has fallen below float precision (default model: about 34 s, so at frame rates up to about
 * 960 Hz); faster, the pixel's occlusion is taken as its stationary value a little early.
 * Shared by the kernels and the host (DeviceFilter). */
#ifndef DT_TIME_INDEX_H
#define DT_TIME_INDEX_H
#define DT_TIME_CYCLE 65535u
#define DT_TIME_NEVER 65535u
#define DT_TIME_RETIRE_AGE 32768u
#define DT_TIME_RETIRE_EVERY 16384u
#define DT_TIME_TABLE (DT_TIME_CYCLE + 1u) /* entries: every index and DT_TIME_NEVER */
#endif
