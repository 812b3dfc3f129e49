// The process heap under a software GL driver: llvmpipe bins every frame's triangles
// into scene memory it allocates in 64 KB blocks from the calling thread's heap and
// frees when the frame is rasterised. glibc hands freed memory at the heap's top back to
// the system once more than 128 KB of it collects there, so each frame faulted its scene
// memory back in, page by page (about 290k page faults in bench_render 3's flights, in
// the thread whose CPU time is the frame's).
#ifndef OROGEN_RENDERER_DRIVER_HEAP_H
#define OROGEN_RENDERER_DRIVER_HEAP_H

// Keeps up to DRIVER_HEAP_KEEP_MB of freed memory at the heap's top for the next frame,
// and serves allocations under DRIVER_HEAP_MMAP_MB from the heap (glibc's own sliding
// threshold stops moving once the trim threshold is set). Once per process; idempotent.
#define DRIVER_HEAP_KEEP_MB 64
#define DRIVER_HEAP_MMAP_MB 4
void driver_heap_keep_freed(void);

#endif
