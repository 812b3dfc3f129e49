// The heap keeps what a software GL driver frees each frame (renderer/driver_heap.h):
// blocks allocated and freed as llvmpipe's scene memory is (64 KB each, 2 MB a frame)
// stay mapped at the heap's top, glibc's releasable top (mallinfo2's keepcost) holding
// them, where it otherwise trims down to its 128 KB pad. Not under the sanitizers, whose
// allocators ignore mallopt.
#include "renderer/driver_heap.h"

#include <malloc.h>
#include <stdlib.h>
#include <string.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stddef.h>
#include <cmocka.h>

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define SANITIZED 1
#else
#define SANITIZED 0
#endif

enum { BLOCKS = 32, BLOCK = 64 * 1024 };

static void freed_frame_memory_stays(void **state) {
    (void)state;
    if (SANITIZED) skip();
    driver_heap_keep_freed();
    driver_heap_keep_freed(); // once is enough; again changes nothing
    for (int frame = 0; frame < 3; frame++) {
        void *block[BLOCKS];
        for (int i = 0; i < BLOCKS; i++) {
            block[i] = malloc(BLOCK);
            assert_non_null(block[i]);
            memset(block[i], frame + 1, BLOCK); // the pages are really used
        }
        for (int i = BLOCKS - 1; i >= 0; i--)
            free(block[i]);
        struct mallinfo2 mi = mallinfo2();
        assert_true(mi.keepcost >= (size_t)(BLOCKS - 2) * BLOCK);
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {cmocka_unit_test(freed_frame_memory_stays)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
