/* Stands in for libOSMesa.so.8 on a GPU machine without it: EGL draws there; every call fails. */
#include <stddef.h>
void* OSMesaCreateContextAttribs(const int* a, void* s) { (void)a; (void)s; return NULL; }
void OSMesaDestroyContext(void* c) { (void)c; }
void* OSMesaGetProcAddress(const char* n) { (void)n; return NULL; }
unsigned char OSMesaMakeCurrent(void* c, void* b, int t, int w, int h) { (void)c; (void)b; (void)t; (void)w; (void)h; return 0; }
