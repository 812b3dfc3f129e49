#include "editor/world/recovery_journal.h"

#include "io/crc32c.h"
#include "io/param_file.h"
#include "io/path_folder.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <sys/uio.h>
#include <time.h>
#include <unistd.h>

// File: header record, then step records. Every record is
//   u32 magic, u32 payload bytes, u32 CRC32C of the payload, payload
// little-endian. The header's payload: u32 version, state id (32 bytes, NUL padded),
// i64 start time, u32 bytes + text of the base parameters (0: none, the world's file
// has them), and in version 2 u32 bytes + text of what the base was made from. A step's: u8 kind,
// u64 session id, i64 time, u16 label bytes, label, u32 tiles x (i32 layer face level tx ty, u8
// was_pristine, u32 bytes, delta), u32 dirty areas x (i32 layer face, i64 x0 z0 x1 z1), u8
// has_params (then u32 bytes
// + text of the parameters before and after).
#define HEADER_MAGIC 0x4A52474Fu  // "OGRJ"
#define RECORD_MAGIC 0x5252474Fu  // "OGRR"
#define JOURNAL_VERSION 1u        // parameters alone
#define JOURNAL_VERSION_SOURCE 2u // and a base source (an older Orogen refuses it)
#define RECORD_HEAD_BYTES 12
// A record larger than this is damage, not a step (a step holds compressed deltas).
#define RECORD_MAX_BYTES ((size_t)1 << 31)

struct recovery_journal {
    int fd;
    uint32_t session; // random: tells this session's step ids from a recovered one's
    char path[4200];
    pthread_t flusher, writer;
    pthread_mutex_t lock;
    pthread_cond_t wake;       // the flusher's: a record was written
    pthread_cond_t work, idle; // the writer's: a record handed over; none left to write
    int dirty, stop, failed;
    // The record handed to the writer, at most one (NULL: none): an append waits for the
    // record before it to be written, so a kill loses at most the step whose append
    // returned last, and only while its write runs. Its pieces point into the step's
    // deltas: the history waits (history_set_reader) before it changes or frees one.
    struct record *handed;
    int writing;     // the writer is writing one (handed is NULL meanwhile)
    int write_errno; // a failed write (the file ends in a torn record): no more appends
    int stop_writer;
};

// ---- bytes -------------------------------------------------------------------------

typedef struct buf {
    uint8_t *p;
    size_t len, cap;
    int oom;
} buf;

static void put(buf *b, const void *data, size_t n) {
    if (b->oom) return;
    if (b->len + n > b->cap) {
        size_t cap = b->cap ? b->cap : 4096;
        while (cap < b->len + n)
            cap *= 2;
        uint8_t *grown = realloc(b->p, cap);
        if (!grown) {
            b->oom = 1;
            return;
        }
        b->p = grown, b->cap = cap;
    }
    memcpy(b->p + b->len, data, n);
    b->len += n;
}

static void put_u8(buf *b, uint8_t v) {
    put(b, &v, 1);
}
static void put_u16(buf *b, uint16_t v) {
    uint8_t x[2] = {(uint8_t)v, (uint8_t)(v >> 8)};
    put(b, x, 2);
}
static void put_u32(buf *b, uint32_t v) {
    uint8_t x[4] = {(uint8_t)v, (uint8_t)(v >> 8), (uint8_t)(v >> 16), (uint8_t)(v >> 24)};
    put(b, x, 4);
}
static void put_u64(buf *b, uint64_t v) {
    put_u32(b, (uint32_t)v);
    put_u32(b, (uint32_t)(v >> 32));
}

// A reader over a record's payload; running past the end sets bad.
typedef struct cursor {
    const uint8_t *p;
    size_t left;
    int bad;
} cursor;

static const uint8_t *take(cursor *c, size_t n) {
    if (c->bad || n > c->left) {
        c->bad = 1;
        return NULL;
    }
    const uint8_t *p = c->p;
    c->p += n, c->left -= n;
    return p;
}
static uint64_t get_le(cursor *c, size_t n) {
    const uint8_t *p = take(c, n);
    uint64_t v = 0;
    for (size_t i = 0; p && i < n; i++)
        v |= (uint64_t)p[i] << (8 * i);
    return v;
}

// Frames payload as a record of magic: head + payload, checksum filled in.
static void frame(buf *out, uint32_t magic, const buf *payload) {
    put_u32(out, magic);
    put_u32(out, (uint32_t)payload->len);
    put_u32(out, crc32c_update(0, payload->p, payload->len));
    put(out, payload->p, payload->len);
}

// A record is written straight from the step's deltas, with no copy of them (an
// import's step holds hundreds of megabytes): its small fields go to one buffer, and
// the pieces (buffer spans and deltas, in order) to one writev.
typedef struct piece {
    const void *data; // a delta, or NULL: meta bytes [off, off + len)
    size_t off, len;
} piece;

typedef struct record {
    buf meta;
    piece *pieces;
    size_t count, cap, meta_mark;
    int oom;
} record;

static void add_piece(record *r, piece p) {
    if (r->oom) return;
    if (r->count == r->cap) {
        size_t cap = r->cap ? r->cap * 2 : 64;
        piece *grown = realloc(r->pieces, cap * sizeof *grown);
        if (!grown) {
            r->oom = 1;
            return;
        }
        r->pieces = grown, r->cap = cap;
    }
    r->pieces[r->count++] = p;
}

// Ends the meta bytes put since the last piece as a piece of their own.
static void close_meta(record *r) {
    if (r->meta.len > r->meta_mark)
        add_piece(r, (piece){NULL, r->meta_mark, r->meta.len - r->meta_mark});
    r->meta_mark = r->meta.len;
}

static void add_data(record *r, const void *data, size_t len) {
    close_meta(r);
    if (len) add_piece(r, (piece){data, 0, len});
}

static const void *piece_bytes(const record *r, const piece *p) {
    return p->data ? p->data : r->meta.p + p->off;
}

// Writes head + pieces, IOV_MAX at a time, through short writes.
static int write_pieces(int fd, const uint8_t *head, size_t head_len, const record *r) {
    struct iovec iov[IOV_MAX];
    size_t next = 0, skip = 0; // piece index, bytes of it already written
    int n = 0;
    iov[n++] = (struct iovec){(void *)head, head_len};
    for (;;) {
        while (n < IOV_MAX && next < r->count) {
            const piece *p = &r->pieces[next];
            iov[n++] = (struct iovec){(uint8_t *)piece_bytes(r, p) + skip, p->len - skip};
            skip = 0;
            next++;
        }
        if (!n) return 0;
        ssize_t w = writev(fd, iov, n);
        if (w < 0 && errno == EINTR) continue;
        if (w < 0) return -1;
        // Drop what was written; a partly written vector stays, shortened.
        int k = 0;
        size_t done = (size_t)w;
        while (k < n && done >= iov[k].iov_len)
            done -= iov[k++].iov_len;
        if (k < n) {
            iov[k].iov_base = (uint8_t *)iov[k].iov_base + done;
            iov[k].iov_len -= done;
        }
        memmove(iov, iov + k, (size_t)(n - k) * sizeof *iov);
        n -= k;
    }
}

// ---- writing -----------------------------------------------------------------------

static void put_params(buf *b, const world_params *p);

static uint64_t random_u64(void) {
    uint64_t v = 0;
    if (getrandom(&v, sizeof v, 0) != (ssize_t)sizeof v)
        v = (uint64_t)time(NULL) ^ (uint64_t)getpid();
    return v;
}

// The flusher: a record is on disk (fdatasync) within about a second of its write.
static void *flusher_main(void *arg) {
    recovery_journal *j = arg;
    pthread_mutex_lock(&j->lock);
    while (!j->stop) {
        if (!j->dirty) {
            pthread_cond_wait(&j->wake, &j->lock);
            continue;
        }
        // Gathers a second's records: appends meanwhile do not wake it (each one did,
        // and had its own fdatasync at once, beside the commit that wrote it).
        struct timespec until;
        clock_gettime(CLOCK_REALTIME, &until);
        until.tv_sec += 1;
        while (!j->stop && pthread_cond_timedwait(&j->wake, &j->lock, &until) != ETIMEDOUT)
            ;
        j->dirty = 0;
        pthread_mutex_unlock(&j->lock);
        fdatasync(j->fd);
        pthread_mutex_lock(&j->lock);
    }
    pthread_mutex_unlock(&j->lock);
    return NULL;
}

// Tells the flusher a record was written (under the lock).
static void mark_dirty(recovery_journal *j) {
    if (!j->dirty) pthread_cond_signal(&j->wake); // else the flusher is gathering
    j->dirty = 1;
}

static void record_free(record *r) {
    if (!r) return;
    free(r->meta.p);
    free(r->pieces);
    free(r);
}

// Writes one record: its head (magic, length, checksum of the pieces), then the pieces.
static int write_record(int fd, const record *r) {
    size_t len = 0;
    uint32_t crc = 0;
    for (size_t i = 0; i < r->count; i++) {
        crc = crc32c_update(crc, piece_bytes(r, &r->pieces[i]), r->pieces[i].len);
        len += r->pieces[i].len;
    }
    uint8_t head[RECORD_HEAD_BYTES];
    buf b = {.p = head, .cap = sizeof head};
    put_u32(&b, RECORD_MAGIC);
    put_u32(&b, (uint32_t)len);
    put_u32(&b, crc);
    return write_pieces(fd, head, sizeof head, r);
}

// The writer's nice value: below the thread that edits. At the same priority, woken by
// an append on a busy machine (no core free), it took the committing thread's core for
// its write (a one-dab step's append took the write's 38 us instead of 3 us). Its own
// nice (Linux: per thread).
#define WRITER_NICE 10

// The writer: writes each record handed over, in order.
static void *writer_main(void *arg) {
    recovery_journal *j = arg;
    setpriority(PRIO_PROCESS, (id_t)syscall(SYS_gettid), WRITER_NICE);
    pthread_mutex_lock(&j->lock);
    for (;;) {
        if (!j->handed) {
            if (j->stop_writer) break;
            pthread_cond_wait(&j->work, &j->lock);
            continue;
        }
        record *r = j->handed;
        j->handed = NULL;
        j->writing = 1;
        pthread_mutex_unlock(&j->lock);
        int rc = write_record(j->fd, r), e = errno;
        record_free(r);
        pthread_mutex_lock(&j->lock);
        j->writing = 0;
        if (rc != 0)
            j->write_errno = e ? e : EIO;
        else
            mark_dirty(j);
        pthread_cond_broadcast(&j->idle);
    }
    pthread_mutex_unlock(&j->lock);
    return NULL;
}

// Waits (under the lock) until every record handed over is written; -1 with err when a
// write failed.
static int wait_written(recovery_journal *j, og_error *err) {
    while (j->handed || j->writing)
        pthread_cond_wait(&j->idle, &j->lock);
    if (!j->write_errno) return 0;
    return og_error_set(err, "%s: cannot write the recovery journal: %s", j->path,
                        strerror(j->write_errno));
}

static void stop_flusher(recovery_journal *j) {
    pthread_mutex_lock(&j->lock);
    j->stop = 1;
    pthread_cond_signal(&j->wake);
    pthread_mutex_unlock(&j->lock);
    pthread_join(j->flusher, NULL);
}

// Makes the file's name durable: its folder is synced once, when it is created.
static void sync_folder(const char *path) {
    path_sync_folder(path);
}

recovery_journal *recovery_journal_open(const char *path, const char *state_id,
                                        const world_params *base, const char *base_source,
                                        size_t keep_bytes, og_error *err) {
    const int has_source = base && base_source && *base_source;
    if (has_source && strlen(base_source) >= RECOVERY_SOURCE_MAX) {
        og_error_set(err, "%s: the world's source description is too long", path);
        return NULL;
    }
    recovery_journal *j = calloc(1, sizeof *j);
    if (!j) {
        og_error_set(err, "%s: out of memory", path);
        return NULL;
    }
    snprintf(j->path, sizeof j->path, "%s", path);
    j->session = (uint32_t)random_u64();
    int flags = O_WRONLY | O_CREAT | O_CLOEXEC | O_APPEND | (keep_bytes ? 0 : O_TRUNC);
    j->fd = open(path, flags, 0644);
    if (j->fd < 0) {
        og_error_set(err, "%s: cannot write the recovery journal: %s", path, strerror(errno));
        free(j);
        return NULL;
    }
    int rc = 0;
    if (keep_bytes) {
        rc = ftruncate(j->fd, (off_t)keep_bytes); // drops a torn tail before appending
    } else {
        buf payload = {0}, out = {0};
        put_u32(&payload, has_source ? JOURNAL_VERSION_SOURCE : JOURNAL_VERSION);
        char id[RECOVERY_STATE_CHARS] = {0};
        memcpy(id, state_id, strnlen(state_id, sizeof id));
        put(&payload, id, sizeof id);
        put_u64(&payload, (uint64_t)time(NULL));
        if (base)
            put_params(&payload, base);
        else
            put_u32(&payload, 0);
        if (has_source) {
            put_u32(&payload, (uint32_t)strlen(base_source));
            put(&payload, base_source, strlen(base_source));
        }
        frame(&out, HEADER_MAGIC, &payload);
        rc = payload.oom || out.oom ? -1 : write_pieces(j->fd, out.p, out.len, &(record){0});
        if (rc == 0) rc = fdatasync(j->fd);
        free(payload.p);
        free(out.p);
    }
    if (rc != 0) {
        og_error_set(err, "%s: cannot write the recovery journal: %s", path, strerror(errno));
        close(j->fd);
        free(j);
        return NULL;
    }
    if (!keep_bytes) sync_folder(path);
    flock(j->fd, LOCK_EX | LOCK_NB); // held while open: recovery_journal_in_use says so
    pthread_mutex_init(&j->lock, NULL);
    pthread_cond_init(&j->wake, NULL);
    pthread_cond_init(&j->work, NULL);
    pthread_cond_init(&j->idle, NULL);
    int flusher = pthread_create(&j->flusher, NULL, flusher_main, j) == 0;
    if (!flusher || pthread_create(&j->writer, NULL, writer_main, j) != 0) {
        og_error_set(err, "%s: cannot start the journal's threads", path);
        if (flusher) stop_flusher(j);
        pthread_mutex_destroy(&j->lock);
        pthread_cond_destroy(&j->wake);
        pthread_cond_destroy(&j->work);
        pthread_cond_destroy(&j->idle);
        close(j->fd);
        free(j);
        return NULL;
    }
    return j;
}

static void put_params(buf *b, const world_params *p) {
    char *text = world_params_format(p);
    size_t n = text ? strlen(text) : 0;
    if (!text) b->oom = 1;
    put_u32(b, (uint32_t)n);
    put(b, text ? text : "", n);
    free(text);
}

int recovery_journal_append(recovery_journal *j, recovery_kind kind, const history_step *s,
                            og_error *err) {
    record *r = calloc(1, sizeof *r);
    if (!r) return og_error_set(err, "%s: out of memory writing the recovery journal", j->path);
    buf *m = &r->meta;
    put_u8(m, (uint8_t)kind);
    put_u64(m, (uint64_t)j->session << 32 | (uint32_t)s->id);
    put_u64(m, (uint64_t)time(NULL));
    size_t label = strnlen(s->label, sizeof s->label);
    put_u16(m, (uint16_t)label);
    put(m, s->label, label);
    put_u32(m, (uint32_t)s->tile_count);
    for (size_t i = 0; i < s->tile_count; i++) {
        const history_tile *t = &s->tiles[i];
        put_u32(m, (uint32_t)t->key.layer);
        put_u32(m, (uint32_t)t->key.face);
        put_u32(m, (uint32_t)t->key.level);
        put_u32(m, (uint32_t)t->key.tx);
        put_u32(m, (uint32_t)t->key.ty);
        put_u8(m, (uint8_t)(t->was_pristine != 0));
        put_u32(m, (uint32_t)t->bytes);
        add_data(r, t->delta, t->bytes);
    }
    put_u32(m, (uint32_t)s->dirty_count);
    for (size_t i = 0; i < s->dirty_count; i++) {
        const dirty_rect *d = &s->dirty[i];
        put_u32(m, (uint32_t)d->layer);
        put_u32(m, (uint32_t)d->face);
        put_u64(m, (uint64_t)d->rect.x0);
        put_u64(m, (uint64_t)d->rect.z0);
        put_u64(m, (uint64_t)d->rect.x1);
        put_u64(m, (uint64_t)d->rect.z1);
    }
    put_u8(m, (uint8_t)(s->has_params != 0));
    if (s->has_params) {
        put_params(m, &s->params->before);
        put_params(m, &s->params->after);
    }
    close_meta(r);
    pthread_mutex_lock(&j->lock);
    // The record before this one written (or its failure known) before this one goes.
    int rc = wait_written(j, err);
    if (rc == 0 && (m->oom || r->oom))
        rc = og_error_set(err, "%s: out of memory writing the recovery journal", j->path);
    if (rc == 0) j->handed = r;
    pthread_mutex_unlock(&j->lock);
    if (rc == 0)
        pthread_cond_signal(&j->work); // unlocked: the writer need not wait for the lock
    else
        record_free(r);
    return rc;
}

int recovery_journal_wait(recovery_journal *j, og_error *err) {
    if (!j) return 0;
    pthread_mutex_lock(&j->lock);
    int rc = wait_written(j, err);
    pthread_mutex_unlock(&j->lock);
    return rc;
}

void recovery_journal_close(recovery_journal *j) {
    if (!j) return;
    pthread_mutex_lock(&j->lock); // the record handed over is written first
    j->stop_writer = 1;
    pthread_cond_signal(&j->work);
    pthread_mutex_unlock(&j->lock);
    pthread_join(j->writer, NULL);
    stop_flusher(j);
    fdatasync(j->fd);
    close(j->fd);
    pthread_mutex_destroy(&j->lock);
    pthread_cond_destroy(&j->wake);
    pthread_cond_destroy(&j->work);
    pthread_cond_destroy(&j->idle);
    free(j);
}

// ---- reading -----------------------------------------------------------------------

static int get_params(cursor *c, world_params *p) {
    uint32_t n = (uint32_t)get_le(c, 4);
    const uint8_t *text = take(c, n);
    if (!text) return -1;
    param_file pf;
    if (param_file_parse((const char *)text, n, &pf) != 0) return -1;
    world_params_default(p, WORLD_FLAT);
    for (size_t i = 0; i < pf.count; i++)
        if (!strcmp(pf.entries[i].key, "kind"))
            world_params_default(p, !strcmp(pf.entries[i].value, "planet") ? WORLD_PLANET
                                                                           : WORLD_FLAT);
    int rc = 0;
    for (size_t i = 0; i < pf.count && rc == 0; i++)
        rc = world_params_read_entry(p, pf.entries[i].key, pf.entries[i].value, NULL) == 0 ? 0 : -1;
    layer_table_finish(&p->layers, NULL);
    material_rules_finish(&p->material_rules);
    if (p->kind == WORLD_PLANET) material_rules_planet_adopt(&p->material_rules);
    param_file_free(&pf);
    return rc;
}

// Decodes a step record's payload; NULL when it does not parse (damage).
static history_step *decode_step(cursor *c, recovery_kind *kind, uint64_t *session_id) {
    *kind = (recovery_kind)get_le(c, 1);
    *session_id = get_le(c, 8);
    get_le(c, 8); // the time: read by the scan
    size_t label_len = (size_t)get_le(c, 2);
    const uint8_t *label = take(c, label_len);
    if (c->bad || *kind < RECOVERY_STEP || *kind > RECOVERY_REDO) return NULL;
    char text[128];
    snprintf(text, sizeof text, "%.*s", (int)(label_len < 127 ? label_len : 127),
             (const char *)label);
    history_step *s = history_step_new(text);
    if (!s) return NULL;
    uint32_t tiles = (uint32_t)get_le(c, 4);
    for (uint32_t i = 0; i < tiles && !c->bad; i++) {
        tile_key key;
        key.layer = (int)(int32_t)get_le(c, 4);
        key.face = (int)(int32_t)get_le(c, 4);
        key.level = (int)(int32_t)get_le(c, 4);
        key.tx = (int32_t)get_le(c, 4);
        key.ty = (int32_t)get_le(c, 4);
        int pristine = (int)get_le(c, 1);
        size_t bytes = (size_t)get_le(c, 4);
        const uint8_t *delta = take(c, bytes);
        if (!delta || key.layer < 0 || tile_key_kind(key) >= TILE_LAYER_COUNT) {
            c->bad = 1;
            break;
        }
        void *copy = malloc(bytes ? bytes : 1);
        if (!copy || history_step_add_delta(s, key, pristine, copy, bytes) != 0) {
            free(copy);
            c->bad = 1;
            break;
        }
        memcpy(copy, delta, bytes);
    }
    uint32_t dirty = (uint32_t)get_le(c, 4);
    for (uint32_t i = 0; i < dirty && !c->bad; i++) {
        dirty_rect d;
        d.layer = (tile_layer)(int32_t)get_le(c, 4);
        d.face = (int)(int32_t)get_le(c, 4);
        d.rect.x0 = (int64_t)get_le(c, 8);
        d.rect.z0 = (int64_t)get_le(c, 8);
        d.rect.x1 = (int64_t)get_le(c, 8);
        d.rect.z1 = (int64_t)get_le(c, 8);
        if (!c->bad && history_step_add_dirty(s, d) != 0) c->bad = 1;
    }
    if (get_le(c, 1) && !c->bad) {
        world_params before, after;
        if (get_params(c, &before) != 0 || get_params(c, &after) != 0 ||
            history_step_set_params(s, &before, &after) != 0)
            c->bad = 1;
    }
    if (c->bad || c->left) { // a record is exactly its fields
        history_step_free(s);
        return NULL;
    }
    return s;
}

int recovery_journal_read(const char *path, recovery_scan *scan,
                          int (*fn)(void *user, recovery_kind kind, uint64_t session_id,
                                    history_step *step, og_error *err),
                          void *user, og_error *err) {
    memset(scan, 0, sizeof *scan);
    int fd = open(path, O_RDONLY | O_CLOEXEC | O_NONBLOCK); // a FIFO is refused, not waited on
    if (fd < 0) return og_error_set(err, "%s: cannot open: %s", path, strerror(errno));
    struct stat st;
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        close(fd);
        return og_error_set(err,
                            "%s: not a recovery journal (not a regular file: a FIFO, device "
                            "or folder is not read)",
                            path);
    }
    size_t size = (size_t)st.st_size;
    uint8_t *data = malloc(size ? size : 1);
    size_t got = 0;
    while (data && got < size) {
        ssize_t n = read(fd, data + got, size - got);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        got += (size_t)n;
    }
    close(fd);
    if (!data) return og_error_set(err, "%s: out of memory", path);
    size = got;
    int rc = 0;
    size_t pos = 0;
    for (int header = 1; pos + RECORD_HEAD_BYTES <= size; header = 0) {
        cursor head = {data + pos, RECORD_HEAD_BYTES, 0};
        uint32_t magic = (uint32_t)get_le(&head, 4), len = (uint32_t)get_le(&head, 4),
                 crc = (uint32_t)get_le(&head, 4);
        if (magic != (header ? HEADER_MAGIC : RECORD_MAGIC) || len > RECORD_MAX_BYTES ||
            len > size - pos - RECORD_HEAD_BYTES)
            break;
        const uint8_t *payload = data + pos + RECORD_HEAD_BYTES;
        if (crc32c_update(0, payload, len) != crc) break;
        cursor c = {payload, len, 0};
        if (header) {
            const uint64_t version = get_le(&c, 4);
            if (version != JOURNAL_VERSION && version != JOURNAL_VERSION_SOURCE) break;
            const uint8_t *id = take(&c, RECOVERY_STATE_CHARS);
            if (!id) break;
            memcpy(scan->state_id, id, RECOVERY_STATE_CHARS);
            scan->state_id[RECOVERY_STATE_CHARS] = 0;
            scan->started = scan->last = (int64_t)get_le(&c, 8);
            cursor peek = c;
            uint32_t base_len = (uint32_t)get_le(&peek, 4);
            if (peek.bad) break;
            if (!base_len)
                c = peek;
            else if (get_params(&c, &scan->base) == 0)
                scan->has_base = 1;
            else
                break;
            if (version == JOURNAL_VERSION_SOURCE) {
                uint32_t n = (uint32_t)get_le(&c, 4);
                const uint8_t *text = n < RECOVERY_SOURCE_MAX ? take(&c, n) : NULL;
                if (!text || !scan->has_base) break;
                memcpy(scan->base_source, text, n);
                scan->base_source[n] = 0;
            }
        } else {
            recovery_kind kind;
            uint64_t session_id;
            cursor probe = c;
            take(&probe, 9); // kind and session id
            int64_t when = (int64_t)get_le(&probe, 8);
            history_step *s = decode_step(&c, &kind, &session_id);
            if (!s) break;
            scan->records++;
            scan->last = when;
            if (fn) {
                if (fn(user, kind, session_id, s, err) != 0) {
                    rc = -1;
                    break;
                }
            } else {
                history_step_free(s);
            }
        }
        pos += RECORD_HEAD_BYTES + len;
        scan->valid_bytes = pos;
    }
    free(data);
    if (rc == 0 && scan->valid_bytes == 0)
        return og_error_set(err, "%s: not an Orogen recovery journal (bad or missing header)",
                            path);
    scan->dropped_bytes = size - scan->valid_bytes;
    return rc;
}

int recovery_journal_in_use(const char *path) {
    int fd = open(path, O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0) return 0;
    int busy = flock(fd, LOCK_EX | LOCK_NB) != 0 && errno == EWOULDBLOCK;
    close(fd);
    return busy;
}
