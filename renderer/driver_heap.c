#include "renderer/driver_heap.h"

#include <malloc.h>

void driver_heap_keep_freed(void) {
    static int done;
    if (done) return;
    done = 1;
    // Both settings are advice: a C library that refuses them only costs the faults.
    mallopt(M_TRIM_THRESHOLD, DRIVER_HEAP_KEEP_MB << 20);
    mallopt(M_MMAP_THRESHOLD, DRIVER_HEAP_MMAP_MB << 20);
}
