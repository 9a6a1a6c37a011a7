// The layering rule (docs/architecture.md, "Layers"): src/filter and src/model are device-neutral; they reach
// devices through src/compute (Queue, Buffer) and the atlas through src/atlas, never through API headers.
#error "layering rule: src/filter and src/model must not include <GL/glcorearb.h> (OpenCL, CUDA, EGL and GL headers belong in src/compute/<backend>, src/atlas/gl and src/interop)"
