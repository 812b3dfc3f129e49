#include "editor/edit/snapshot_pool.h"

#include <pthread.h>
#include <stdlib.h>

// Bytes of buffers kept between edits: 64 coarse tiles, enough for a stroke over a few
// tiles with its mip levels; a stamp over hundreds of tiles frees what is past it.
#define SNAPSHOT_POOL_BYTES ((size_t)16 << 20)

// A kept buffer's first bytes link it to the next of its size.
typedef struct kept {
    struct kept *next;
    size_t bytes;
} kept;

static struct {
    pthread_mutex_t lock;
    kept *head;
    size_t bytes;
} pool = {.lock = PTHREAD_MUTEX_INITIALIZER};

void *snapshot_pool_take(size_t bytes) {
    pthread_mutex_lock(&pool.lock);
    for (kept **k = &pool.head; *k; k = &(*k)->next)
        if ((*k)->bytes == bytes) {
            kept *found = *k;
            *k = found->next;
            pool.bytes -= bytes;
            pthread_mutex_unlock(&pool.lock);
            return found;
        }
    pthread_mutex_unlock(&pool.lock);
    return malloc(bytes < sizeof(kept) ? sizeof(kept) : bytes);
}

void snapshot_pool_give(void *p, size_t bytes) {
    if (!p) return;
    pthread_mutex_lock(&pool.lock);
    if (bytes >= sizeof(kept) && pool.bytes + bytes <= SNAPSHOT_POOL_BYTES) {
        kept *k = p;
        *k = (kept){pool.head, bytes};
        pool.head = k;
        pool.bytes += bytes;
        p = NULL;
    }
    pthread_mutex_unlock(&pool.lock);
    free(p);
}
