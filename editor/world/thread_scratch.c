#include "editor/world/thread_scratch.h"

#include <pthread.h>
#include <stdlib.h>

typedef struct scratch {
    void *buffer[SCRATCH_USES];
    size_t cap[SCRATCH_USES];
} scratch;

static pthread_key_t key;
static pthread_once_t once = PTHREAD_ONCE_INIT;

static void free_scratch(void *p) {
    scratch *s = p;
    for (int i = 0; i < SCRATCH_USES; i++)
        free(s->buffer[i]);
    free(s);
}

static void make_key(void) {
    pthread_key_create(&key, free_scratch);
}

void *thread_scratch(thread_scratch_use use, size_t bytes) {
    pthread_once(&once, make_key);
    scratch *s = pthread_getspecific(key);
    if (!s) {
        if (!(s = calloc(1, sizeof *s))) return NULL;
        if (pthread_setspecific(key, s) != 0) {
            free(s);
            return NULL;
        }
    }
    if (s->cap[use] < bytes) {
        void *grown = malloc(bytes); // not realloc: the old contents need not move
        if (!grown) return NULL;
        free(s->buffer[use]);
        s->buffer[use] = grown;
        s->cap[use] = bytes;
    }
    return s->buffer[use];
}
