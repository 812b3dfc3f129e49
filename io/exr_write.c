// OpenEXR scanline file, one FLOAT channel, ZIP_COMPRESSION, as the OpenEXR file
// layout document gives it: magic and version, the header's attributes in name
// order, a table of block offsets, then per block of 16 rows its first row, its size
// and its bytes. A block's bytes are deflated (zlib stream) after OpenEXR's
// reordering (even bytes first, then odd) and byte-delta predictor; a block that
// would not shrink is stored as it is, which readers tell by its size.
//
// The blocks are compressed by a pool of threads into a ring of slots and written in
// order by the calling thread as they complete, so the file is the same whatever the
// thread count and scheduling.
#include "io/exr_write.h"

#include "io/file_kind.h"
#include "io/file_mode.h"
#include "io/path_folder.h"

#include <errno.h>
#include <fcntl.h>
#include <libdeflate.h>
#include <pthread.h>
#include <sched.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

_Static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__,
               "EXR stores little-endian floats: this writer copies them as they are in memory");

// OpenEXR's default ZIP level (OpenEXR 3.1 writes level 4 unless told otherwise), so a
// comparison with its writer is at equal effort; libdeflate's level 4 compresses as
// well or slightly better.
enum { DEFLATE_LEVEL = 4, MAX_THREADS = 16 };

// Header bytes: little-endian values appended to a growing buffer.
typedef struct header {
    unsigned char bytes[512];
    size_t len;
} header;

static void put(header *h, const void *p, size_t n) {
    memcpy(h->bytes + h->len, p, n);
    h->len += n;
}
static void put_i32(header *h, int32_t v) {
    put(h, &v, 4);
}
static void put_f32(header *h, float v) {
    put(h, &v, 4);
}
static void put_str(header *h, const char *s) {
    put(h, s, strlen(s) + 1);
}
static void attribute(header *h, const char *name, const char *type, int32_t size) {
    put_str(h, name);
    put_str(h, type);
    put_i32(h, size);
}

// The required attributes, in name order as OpenEXR writes them.
static void build_header(header *h, int width, int height, const char *channel) {
    static const unsigned char magic[4] = {0x76, 0x2f, 0x31, 0x01};
    put(h, magic, 4);
    put_i32(h, 2); // version 2, single-part scanline, short names
    attribute(h, "channels", "chlist", (int32_t)(strlen(channel) + 1 + 16 + 1));
    put_str(h, channel);
    put_i32(h, 2);                // pixel type FLOAT
    put_i32(h, 0);                // pLinear 0 and three reserved bytes
    put_i32(h, 1), put_i32(h, 1); // x and y sampling
    put(h, "", 1);                // end of the channel list
    attribute(h, "compression", "compression", 1);
    put(h, "\3", 1); // ZIP_COMPRESSION
    for (int i = 0; i < 2; i++) {
        attribute(h, i == 0 ? "dataWindow" : "displayWindow", "box2i", 16);
        put_i32(h, 0), put_i32(h, 0), put_i32(h, width - 1), put_i32(h, height - 1);
    }
    attribute(h, "lineOrder", "lineOrder", 1);
    put(h, "", 1); // INCREASING_Y
    attribute(h, "pixelAspectRatio", "float", 4);
    put_f32(h, 1.0f);
    attribute(h, "screenWindowCenter", "v2f", 8);
    put_f32(h, 0.0f), put_f32(h, 0.0f);
    attribute(h, "screenWindowWidth", "float", 4);
    put_f32(h, 1.0f);
    put(h, "", 1); // end of the header
}

// One compressed block waiting in the ring to be written.
typedef struct slot {
    unsigned char *buffer; // deflated bytes (bound-sized)
    const unsigned char *data;
    size_t size;
    int done;
} slot;

typedef struct writer {
    const float *samples;
    int width, height, blocks;
    size_t block_bytes, bound;
    pthread_mutex_t lock;
    pthread_cond_t changed;
    int next;    // the next block to compress
    int written; // blocks written so far (their slots are free again)
    int failed;  // a compressor could not be made: everyone stops
    int ring;
    slot *slots;
} writer;

typedef struct worker {
    writer *w;
    struct libdeflate_compressor *deflate;
    unsigned char *scratch;
} worker;

// OpenEXR's ZIP preparation of one block, then deflate; stored raw if no smaller.
static void compress_block(worker *k, int b) {
    writer *w = k->w;
    const int rows = w->height - b * EXR_ZIP_BLOCK_ROWS < EXR_ZIP_BLOCK_ROWS
                         ? w->height - b * EXR_ZIP_BLOCK_ROWS
                         : EXR_ZIP_BLOCK_ROWS;
    const size_t n = (size_t)rows * (size_t)w->width * sizeof(float);
    const unsigned char *raw =
        (const unsigned char *)(w->samples + (size_t)b * EXR_ZIP_BLOCK_ROWS * w->width);
    unsigned char *t = k->scratch, *t2 = k->scratch + (n + 1) / 2;
    for (size_t i = 0; i < n / 2; i++) { // n is a multiple of 4
        t[i] = raw[2 * i];
        t2[i] = raw[2 * i + 1];
    }
    // Each byte becomes its difference from the one before it, plus 128 (mod 256);
    // backwards, so every difference reads an unchanged predecessor.
    for (size_t i = n - 1; i > 0; i--)
        t[i] = (unsigned char)(t[i] - t[i - 1] + 128);
    slot *s = &w->slots[b % w->ring];
    size_t packed = libdeflate_zlib_compress(k->deflate, t, n, s->buffer, w->bound);
    if (packed > 0 && packed < n) {
        s->data = s->buffer;
        s->size = packed;
    } else {
        s->data = raw;
        s->size = n;
    }
}

// Takes the next block whose slot is free, if any (lock held). -1: none now.
static int take_block(writer *w) {
    if (w->failed || w->next >= w->blocks || w->next >= w->written + w->ring) return -1;
    return w->next++;
}

static void compress_and_post(worker *k, int b) {
    compress_block(k, b);
    pthread_mutex_lock(&k->w->lock);
    k->w->slots[b % k->w->ring].done = 1;
    pthread_cond_broadcast(&k->w->changed);
}

// A helper thread: compresses blocks until there are none left.
static void *helper_main(void *arg) {
    worker *k = arg;
    writer *w = k->w;
    pthread_mutex_lock(&w->lock);
    for (;;) {
        if (w->failed || w->next >= w->blocks) break;
        int b = take_block(w);
        if (b < 0) {
            pthread_cond_wait(&w->changed, &w->lock);
            continue;
        }
        pthread_mutex_unlock(&w->lock);
        compress_and_post(k, b); // returns with the lock held
    }
    pthread_mutex_unlock(&w->lock);
    return NULL;
}

static int worker_init(worker *k, writer *w) {
    k->w = w;
    k->deflate = libdeflate_alloc_compressor(DEFLATE_LEVEL);
    k->scratch = malloc(w->block_bytes);
    return k->deflate && k->scratch ? 0 : -1;
}

static void worker_free(worker *k) {
    if (k->deflate) libdeflate_free_compressor(k->deflate);
    free(k->scratch);
}

// The cores this process may use (a shard pinned to one core gets one thread).
static int thread_count(void) {
    cpu_set_t set;
    int n = sched_getaffinity(0, sizeof set, &set) == 0 ? CPU_COUNT(&set) : 1;
    return n < 1 ? 1 : n > MAX_THREADS ? MAX_THREADS : n;
}

// Writes the blocks in order as they complete, compressing whatever is free while it
// waits. Returns 0, or -1 with errno from the failed write.
static int write_blocks(writer *w, worker *self, FILE *f, uint64_t *offsets, uint64_t at) {
    pthread_mutex_lock(&w->lock);
    for (int b = 0; b < w->blocks; b++) {
        slot *s = &w->slots[b % w->ring];
        while (!s->done && !w->failed) {
            int mine = take_block(w);
            if (mine < 0) {
                pthread_cond_wait(&w->changed, &w->lock);
                continue;
            }
            pthread_mutex_unlock(&w->lock);
            compress_and_post(self, mine);
        }
        pthread_mutex_unlock(&w->lock);
        if (w->failed) return -1;
        const int32_t head[2] = {b * EXR_ZIP_BLOCK_ROWS, (int32_t)s->size};
        offsets[b] = at;
        if (fwrite(head, sizeof head, 1, f) != 1 || fwrite(s->data, 1, s->size, f) != s->size) {
            pthread_mutex_lock(&w->lock);
            w->failed = 1;
            pthread_cond_broadcast(&w->changed);
            pthread_mutex_unlock(&w->lock);
            return -1;
        }
        at += sizeof head + s->size;
        pthread_mutex_lock(&w->lock);
        s->done = 0;
        w->written = b + 1;
        pthread_cond_broadcast(&w->changed);
    }
    pthread_mutex_unlock(&w->lock);
    return 0;
}

// Header, offset table, blocks, then the table's real values; fflush. -1 with errno.
static int write_file(writer *w, worker *workers, int threads, FILE *f, const header *h) {
    uint64_t *offsets = calloc((size_t)w->blocks, sizeof *offsets);
    if (!offsets) return -1;
    int rc = -1;
    pthread_t helpers[MAX_THREADS];
    int started = 0;
    if (fwrite(h->bytes, 1, h->len, f) != h->len ||
        fwrite(offsets, sizeof *offsets, (size_t)w->blocks, f) != (size_t)w->blocks)
        goto done;
    for (; started < threads - 1; started++)
        if (pthread_create(&helpers[started], NULL, helper_main, &workers[started + 1]) != 0)
            break; // fewer helpers: the writer compresses the rest itself
    rc = write_blocks(w, &workers[0], f, offsets,
                      (uint64_t)h->len + (uint64_t)w->blocks * sizeof *offsets);
    int saved = errno;
    for (int i = 0; i < started; i++)
        pthread_join(helpers[i], NULL);
    errno = saved;
    if (rc == 0 && (fseeko(f, (off_t)h->len, SEEK_SET) != 0 ||
                    fwrite(offsets, sizeof *offsets, (size_t)w->blocks, f) != (size_t)w->blocks ||
                    fflush(f) != 0))
        rc = -1;
done:
    free(offsets);
    return rc;
}

int exr_write_float(const char *path, const float *samples, int width, int height,
                    const char *channel, og_error *err) {
    if (width <= 0 || height <= 0 || width > 65536 || height > 65536)
        return og_error_set(err, "%s: cannot write a %d x %d image (1 to 65536 per side)", path,
                            width, height);
    if (!channel || !*channel || strlen(channel) > 255)
        return og_error_set(err, "%s: EXR channel names are 1 to 255 characters", path);
    if (file_kind_check_replace(path, err) != 0) return -1;

    header h = {.len = 0};
    build_header(&h, width, height, channel);
    writer w = {.samples = samples,
                .width = width,
                .height = height,
                .blocks = (height + EXR_ZIP_BLOCK_ROWS - 1) / EXR_ZIP_BLOCK_ROWS,
                .block_bytes = (size_t)width * EXR_ZIP_BLOCK_ROWS * sizeof(float)};
    const int threads = thread_count();
    w.ring = 4 * threads;
    worker workers[MAX_THREADS] = {{0}};
    int rc = -1, fd = -1, created = 0;
    FILE *f = NULL;
    size_t len = strlen(path);
    char *tmp = malloc(len + 16);
    w.slots = calloc((size_t)w.ring, sizeof *w.slots);
    pthread_mutex_init(&w.lock, NULL);
    pthread_cond_init(&w.changed, NULL);
    if (!tmp || !w.slots) {
        og_error_set(err, "%s: out of memory", path);
        goto done;
    }
    {
        struct libdeflate_compressor *probe = libdeflate_alloc_compressor(DEFLATE_LEVEL);
        w.bound = probe ? libdeflate_zlib_compress_bound(probe, w.block_bytes) : 0;
        if (probe) libdeflate_free_compressor(probe);
    }
    for (int i = 0; i < w.ring; i++)
        if (!(w.slots[i].buffer = malloc(w.bound ? w.bound : 1)) || !w.bound) {
            og_error_set(err, "%s: out of memory for compression buffers", path);
            goto done;
        }
    for (int i = 0; i < threads; i++)
        if (worker_init(&workers[i], &w) != 0) {
            og_error_set(err, "%s: out of memory for a compressor", path);
            goto done;
        }

    snprintf(tmp, len + 16, "%s.tmp-XXXXXX", path);
    fd = mkstemp(tmp);
    if (fd < 0) {
        og_error_set(err, "%s: cannot create a temp file beside it: %s", path, strerror(errno));
        goto done;
    }
    created = 1;
    fchmod(fd, og_new_file_mode()); // mkstemp's 0600 would carry over to the final file
    f = fdopen(fd, "wb");
    if (!f) {
        og_error_set(err, "%s: cannot write: %s", path, strerror(errno));
        goto done;
    }
    fd = -1;
    setvbuf(f, NULL, _IOFBF, 1 << 20);
    if (write_file(&w, workers, threads, f, &h) != 0) {
        og_error_set(err, "%s: cannot write: %s", path, strerror(errno));
    } else if (fsync(fileno(f)) != 0) {
        og_error_set(err, "%s: cannot flush the file to disk: %s", path, strerror(errno));
    } else if (fclose(f) != 0) {
        f = NULL;
        og_error_set(err, "%s: cannot write: %s", path, strerror(errno));
    } else if (f = NULL, rename(tmp, path) != 0) {
        og_error_set(err, "%s: cannot rename the temp file into place: %s", path, strerror(errno));
    } else {
        path_sync_folder(path); // best effort: the file itself is durable
        rc = 0;
    }
done:
    if (f) fclose(f);
    if (fd >= 0) close(fd);
    if (rc != 0 && created) unlink(tmp);
    for (int i = 0; i < threads; i++)
        worker_free(&workers[i]);
    for (int i = 0; w.slots && i < w.ring; i++)
        free(w.slots[i].buffer);
    free(w.slots);
    free(tmp);
    pthread_cond_destroy(&w.changed);
    pthread_mutex_destroy(&w.lock);
    return rc;
}
