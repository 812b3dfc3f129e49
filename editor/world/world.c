#include "editor/world/world.h"

#include "editor/gen/gen.h"
#include "editor/layers/layer_blend.h"
#include "editor/world/history.h"
#include "editor/params/world_grid.h"
#include "editor/world/journal_files.h"
#include "io/file_lock.h"

#include <time.h>

#include <errno.h>
#include <signal.h>
#include <stdarg.h>
#include <inttypes.h>
#include <ftw.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

// What the cache's workers generate from: a private copy of the parameters, so a
// `generate` never changes them under a running worker.
typedef struct world_generation {
    world_params params;
} world_generation;

struct world {
    world_params params;
    world_settings settings;
    char path[4096];        // parameter file; "" until saved
    char scratch_dir[4096]; // the journal's folder in $TMPDIR
    // Errors the parameter file had when loaded (those lines kept their defaults, so
    // saving over it would lose them), and the first few as "LINE: error: ..." lines.
    // Both are cleared by a save.
    int file_errors;
    char file_problems[1024];
    // Why the world must not be saved over its own files ("" when it may): its tile
    // store is missing, empty or another world's. Cleared by a (forced) save.
    char read_only[4608];
    long open_in;   // the live process that has the world open (its read_only says so), or 0
    file_lock lock; // held on the tile store's lock file while the world is ours to save
    // Crash recovery: the saved state edits build on (the tile store's state_id, "" for
    // none), the journal beside the parameter file, this session's writer (opened at its
    // first record), and a previous session's journal on the same state, unrecovered.
    char state_id[RECOVERY_STATE_CHARS + 1];
    char recover_path[4300];
    recovery_journal *rj;
    int journal_paused, journal_failed;
    size_t recoverable;
    int64_t recoverable_when;
    // A never-saved world journals under the recovery folder, onto the parameters it
    // was created with.
    int unsaved_journal;
    int journal_fresh; // the journal was begun by this session, not taken over
    int keep_journal;  // the script driving this run failed: its journal stays
    world_params base_params;
    char *base_source; // world_set_base_source: the journal's base beside base_params
    // Edits go to the journal (a scratch store) until saved; the world's own store,
    // when it has one, is only read until `save` merges the journal into it. So a
    // world closed without saving leaves its files exactly as they were.
    tile_store *journal;
    tile_store *store; // NULL until the world has been saved (or loaded with its tiles)
    tile_cache *cache;
    world_generation *gen;
    history *history;
    world_events *own_events; // the private hub when settings.events is NULL
};

static int generation_source(void *user, tile_key key, void *out) {
    const world_generation *g = user;
    int32_t slot = tile_key_slot(key);
    if (slot == 0) return gen_tile(&g->params, key, out);
    key.layer = tile_key_kind(key);
    // Layers hold heights or material weights (paint layers); the base's are generated.
    if (key.layer != TILE_LAYER_COARSE && key.layer != TILE_LAYER_MATERIAL) return -1;
    if (slot == TILE_SLOT_BASE) return gen_tile(&g->params, key, out);
    int faces = g->params.kind == WORLD_PLANET ? 6 : 1;
    if (key.face < 0 || key.face >= faces || key.level < 0 || key.level > TILE_MAX_LEVEL) return -1;
    if (slot > LAYER_ID_MAX) { // a painted mask's coverage where it was never painted
        memset(out, 0, tile_layer_bytes(TILE_LAYER_COARSE));
        return 0;
    }
    if (key.layer == TILE_LAYER_MATERIAL) { // a paint layer where it was never painted: no
        memset(out, 0, tile_layer_bytes(TILE_LAYER_MATERIAL)); // coverage (paint_blend.h)
        return 0;
    }
    // An edit layer's tile it never wrote: nothing there (NaN, editor/layers/layer_blend.h).
    float *f = out;
    for (size_t i = 0; i < TILE_SAMPLES; i++)
        f[i] = NAN;
    return 0;
}

static void default_warn(void *user, const char *message) {
    (void)user;
    fprintf(stderr, "%s\n", message);
}

static int check_params(const world_params *p, og_error *err) {
    if (world_params_validate(p, err) != 0) return -1;
    if (p->kind == WORLD_PLANET && p->generator == GEN_DIAMOND_SQUARE)
        return og_error_set(err, "generator: diamond_square works on flat worlds only; planets "
                                 "use fbm, fbm_advanced, ridged, faults or flat");
    return 0;
}

// A cache over the world's journal and base store generating from params. The old
// cache (if any) keeps running until the caller swaps the new one in.
static int make_cache(world *w, const world_params *params, tile_store *base, tile_cache **cache,
                      world_generation **gen, og_error *err) {
    world_generation *g = malloc(sizeof *g);
    if (!g) return og_error_set(err, "out of memory");
    g->params = *params;
    tile_cache_desc d = {
        .budget_bytes = w->settings.cache_budget_bytes,
        .workers = w->settings.workers,
        .source = generation_source,
        .source_user = g,
        .store = w->journal,
        .base_store = base,
        .warn = w->settings.warn,
        .warn_user = w->settings.warn_user,
    };
    tile_cache *c = tile_cache_create(&d, err);
    if (!c) {
        free(g);
        return -1;
    }
    *cache = c;
    *gen = g;
    return 0;
}

static int start_cache(world *w, og_error *err) {
    return make_cache(w, &w->params, w->store, &w->cache, &w->gen, err);
}

static int stop_cache(world *w, og_error *err) {
    int rc = tile_cache_destroy(w->cache, err);
    free(w->gen);
    w->cache = NULL;
    w->gen = NULL;
    return rc;
}

// Replaces the running cache with a new one (already running); the old one's dirty
// tiles were flushed by the caller.
static void swap_cache(world *w, tile_cache *cache, world_generation *gen) {
    og_error err = {{0}};
    if (stop_cache(w, &err) != 0) w->settings.warn(w->settings.warn_user, err.msg);
    w->cache = cache;
    w->gen = gen;
}

static int remove_entry(const char *path, const struct stat *st, int flag, struct FTW *ftw) {
    (void)st, (void)flag, (void)ftw;
    return remove(path);
}

static void close_stores(world *w) {
    tile_store_close(w->store);
    w->store = NULL;
    tile_store_close(w->journal);
    w->journal = NULL;
    if (w->scratch_dir[0]) {
        nftw(w->scratch_dir, remove_entry, 8, FTW_DEPTH | FTW_PHYS);
        w->scratch_dir[0] = 0;
    }
}

static int open_journal(world *w, og_error *err) {
    const char *tmp = getenv("TMPDIR");
    snprintf(w->scratch_dir, sizeof w->scratch_dir, "%s/orogen-scratch-XXXXXX",
             tmp && *tmp ? tmp : "/tmp");
    if (!mkdtemp(w->scratch_dir)) {
        int e = errno;
        w->scratch_dir[0] = 0;
        return og_error_set(err, "cannot create a scratch folder for unsaved edits in %s: %s",
                            tmp && *tmp ? tmp : "/tmp", strerror(e));
    }
    char path[4200];
    snprintf(path, sizeof path, "%s/unsaved.tiles", w->scratch_dir);
    w->journal = tile_store_open(path, err);
    if (!w->journal) {
        close_stores(w);
        return -1;
    }
    return 0;
}

// The crash journal's writer reads the steps' deltas (recovery_journal_append): the
// history waits for it before it frees or replaces one.
static void journal_written(void *user) {
    world_journal_wait(user);
}

static world *world_alloc(const world_params *params, const world_settings *settings) {
    world *w = calloc(1, sizeof *w);
    if (!w) return NULL;
    w->lock.fd = -1;
    w->params = *params;
    // Every world has a layer for the tools to write to.
    if (!w->params.layers.count) layer_table_default(&w->params.layers);
    if (settings) w->settings = *settings;
    if (!w->settings.warn) w->settings.warn = default_warn;
    if (!w->settings.events) w->settings.events = w->own_events = world_events_create();
    w->history = history_create(w->settings.history_budget_bytes);
    if (w->history) history_set_reader(w->history, journal_written, w);
    if (!w->history || !w->settings.events) {
        history_destroy(w->history);
        world_events_release(w->own_events);
        free(w);
        return NULL;
    }
    return w;
}

world *world_create(const world_params *params, const world_settings *settings, og_error *err) {
    if (check_params(params, err) != 0) return NULL;
    world *w = world_alloc(params, settings);
    if (w) w->base_params = w->params;
    if (!w) {
        og_error_set(err, "out of memory");
        return NULL;
    }
    if (open_journal(w, err) != 0 || start_cache(w, err) != 0) {
        world_close(w);
        return NULL;
    }
    return w;
}

static void forward_report(void *user, const char *message) {
    const world_settings *s = user;
    if (s && s->warn)
        s->warn(s->warn_user, message);
    else
        default_warn(NULL, message);
}

// Forwards load diagnostics and keeps the errors among them for world_save's refusal.
typedef struct load_report {
    const world_settings *settings;
    size_t path_len;
    char problems[1024];
} load_report;

static void collect_report(void *user, const char *message) {
    load_report *r = user;
    forward_report((void *)r->settings, message);
    if (!strstr(message, ": error: ")) return;
    // "PATH:LINE: error: ..." is kept without its path.
    const char *tail = strlen(message) > r->path_len ? message + r->path_len : message;
    if (*tail == ':') tail++;
    size_t n = strlen(r->problems);
    if (n + 8 < sizeof r->problems)
        snprintf(r->problems + n, sizeof r->problems - n, "%s%s", n ? "\n" : "", tail);
}

// Checks the tile store against what the parameter file recorded at its last save.
static void warn_path(world *w, const char *path, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
static void warn_path(world *w, const char *path, const char *fmt, ...) {
    char msg[9000], text[4800];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    snprintf(msg, sizeof msg, "%s: %s", path, text);
    w->settings.warn(w->settings.warn_user, msg);
}

// Returns the store to use (NULL: none, the generated terrain) with w->read_only
// saying why when the store is missing, empty, another world's or short of tiles;
// -1 only when the store cannot be opened at all.
static int open_checked_store(world *w, const char *tiles, og_error *err) {
    const world_params *p = &w->params;
    struct stat st;
    int exists = stat(tiles, &st) == 0;
    const char *ro = "opened read-only ('save force=1' writes over it, save to another file "
                     "keeps it)";
    if (!exists) {
        // A store that held no tiles when saved loses nothing by being gone (a world file
        // copied on its own); one of an unknown count (an older file) might have.
        if (p->tiles_saved > 0 || (p->tiles_saved < 0 && p->tiles_id[0]))
            snprintf(w->read_only, sizeof w->read_only,
                     "its tile store %s is missing (it held %" PRId64
                     " tiles when saved); showing generated terrain there; %s",
                     tiles, p->tiles_saved > 0 ? p->tiles_saved : 0, ro);
        return 0;
    }
    if (S_ISREG(st.st_mode) && st.st_size == 0) {
        // Opening it would make it a fresh, empty store; leave it as it is.
        snprintf(w->read_only, sizeof w->read_only,
                 "its tile store %s is empty (0 bytes); showing generated terrain there; %s", tiles,
                 ro);
        return 0;
    }
    if (!(w->store = tile_store_open_readable(tiles, err))) return -1;
    if (tile_store_warning(w->store)[0]) warn_path(w, tiles, "%s", tile_store_warning(w->store));
    if (tile_store_read_only(w->store)[0]) {
        snprintf(w->read_only, sizeof w->read_only,
                 "its tile store %s cannot be written: %s; opened read-only (save to another "
                 "file keeps your edits)",
                 tiles, tile_store_read_only(w->store));
        return 0;
    }
    char id[64] = "";
    int has_id = tile_store_get_meta(w->store, "world_id", id, sizeof id, err);
    if (has_id < 0) return -1;
    int64_t count = tile_store_count(w->store, -1);
    if (p->tiles_id[0] && (has_id == 0 || strcmp(id, p->tiles_id) != 0)) {
        snprintf(w->read_only, sizeof w->read_only,
                 "its tile store %s belongs to another world (id %s, this file expects %s); "
                 "showing generated terrain there; %s",
                 tiles, has_id ? id : "none", p->tiles_id, ro);
        tile_store_close(w->store); // its tiles are not this world's
        w->store = NULL;
    } else if (p->tiles_saved > 0 && count < p->tiles_saved) {
        snprintf(w->read_only, sizeof w->read_only,
                 "its tile store %s holds %" PRId64 " tiles, %" PRId64 " when saved; %s", tiles,
                 count, p->tiles_saved, ro);
    }
    return 0;
}

// The lock file beside a tile store.
static void lock_path_of(const char *tiles, char *out, size_t len) {
    snprintf(out, len, "%s.lock", tiles);
}

// Takes the lock of the world's files at tiles for w; *owner gets the pid of a live
// process holding it instead (then 1 is returned). A lock left by a dead process is
// taken over, with a warning.
static int lock_files(world *w, const char *tiles, long *owner, og_error *err) {
    char path[4300];
    lock_path_of(tiles, path, sizeof path);
    file_lock l;
    long stale = 0;
    file_lock_result r = file_lock_acquire(&l, path, owner, &stale, err);
    if (r == FILE_LOCK_ERROR) return -1;
    if (r == FILE_LOCK_REFUSED) { // never written through: the world is not ours to save
        snprintf(w->read_only, sizeof w->read_only,
                 "%s; opened read-only, save to another file keeps your edits", err->msg);
        return 0;
    }
    // This process holds it: a world being replaced by a load of the same files. It
    // releases the lock when closed; save takes it then.
    if (r == FILE_LOCK_HELD && *owner == (long)getpid()) return 0;
    if (r == FILE_LOCK_HELD) return 1;
    if (r == FILE_LOCK_ACQUIRED && stale && stale != (long)getpid()) {
        // Nobody held the lock, so its writer is gone; a live process of that pid is
        // another one (the pid was reused, or the file was copied).
        if (kill((pid_t)stale, 0) == 0 || errno == EPERM)
            warn_path(w, path,
                      "warning: took over a lock file naming process %ld, which does not hold "
                      "it (that pid is now another process's)",
                      stale);
        else
            warn_path(w, path,
                      "warning: took over the lock of process %ld, which is no longer running",
                      stale);
    }
    file_lock_release(&w->lock);
    w->lock = l; // FILE_LOCK_UNAVAILABLE leaves fd -1: a read-only folder needs no guard
    return 0;
}

static void format_time(int64_t t, char *out, size_t len) {
    time_t tt = (time_t)t;
    struct tm tm;
    if (!localtime_r(&tt, &tm) || !strftime(out, len, "%Y-%m-%d %H:%M:%S", &tm))
        snprintf(out, len, "%lld", (long long)t);
}

// The journal a session that did not save left beside the world: offered when it
// builds on the state the world was saved in, reported when it does not.
static void count_journal(void *user, const char *path) {
    (void)path;
    ++*(size_t *)user;
}

static void find_recoverable(world *w) {
    snprintf(w->recover_path, sizeof w->recover_path, "%s.recover", w->path);
    size_t journals = 0;
    journal_files_each(w->recover_path, count_journal, &journals);
    struct stat own;
    size_t aside = journals - (lstat(w->recover_path, &own) == 0);
    if (aside)
        warn_path(w, w->path,
                  "warning: %zu journal%s of earlier sessions %s set aside: 'recover list' lists "
                  "them, 'recover FILE' restores one",
                  aside, aside == 1 ? "" : "s", aside == 1 ? "is" : "are");
    if (w->store) {
        og_error ignored;
        if (tile_store_get_meta(w->store, "state_id", w->state_id, sizeof w->state_id, &ignored) !=
            1)
            w->state_id[0] = 0;
    }
    if (access(w->recover_path, F_OK) != 0) return;
    recovery_scan scan;
    og_error why;
    if (recovery_journal_read(w->recover_path, &scan, NULL, NULL, &why) != 0) {
        warn_path(w, w->path, "warning: %s; it is left as it is", why.msg);
        return;
    }
    char when[64];
    format_time(scan.last, when, sizeof when);
    if (strcmp(scan.state_id, w->state_id) != 0) {
        warn_path(w, w->path,
                  "warning: the recovery journal %s (from %s) builds on another saved state of "
                  "this world and cannot be replayed on this one; 'recover discard' removes it",
                  w->recover_path, when);
        return;
    }
    if (!scan.records) return;
    w->recoverable = scan.records;
    w->recoverable_when = scan.last;
    char torn[128] = "";
    if (scan.dropped_bytes)
        snprintf(torn, sizeof torn, "; a torn last step of %zu bytes is left out",
                 scan.dropped_bytes);
    warn_path(w, w->path,
              "warning: unsaved edits from %s (%zu step%s%s) can be recovered: 'recover' "
              "restores them, 'recover discard' drops them",
              when, scan.records, scan.records == 1 ? "" : "s", torn);
}

static int collect_composite(void *user, tile_key key) {
    tile_key **keys = user;
    if (key.layer != TILE_LAYER_COARSE || key.level != 0) return 0;
    size_t n = (size_t)(*keys)[0].tx; // the count rides in element 0
    tile_key *grown = realloc(*keys, (n + 2) * sizeof **keys);
    if (!grown) return 1;
    grown[n + 1] = key;
    grown[0].tx = (int32_t)(n + 1);
    *keys = grown;
    return 0;
}

// A world saved before layers: its sculpted heights become the difference, in its one
// layer, from the generated terrain, so hiding or toning the layer down works on them
// too. The composite tiles stay as saved (the same `hash`); each layer sample is solved
// so that base + layer gives the saved height back exactly (layer_blend_solve).
static int adopt_edits_as_layer(world *w, og_error *err) {
    tile_key *keys = calloc(1, sizeof *keys);
    if (!keys) return og_error_set(err, "out of memory");
    if (tile_store_each(w->store, collect_composite, &keys, err) != 0) {
        free(keys);
        return -1;
    }
    size_t n = (size_t)keys[0].tx;
    const layer_info *layer = &w->params.layers.layers[0];
    int rc = 0;
    for (size_t i = 1; i <= n && rc == 0; i++) {
        tile_key ck = keys[i], bk = ck, lk = ck;
        bk.layer = tile_layer_in_slot(TILE_LAYER_COARSE, TILE_SLOT_BASE);
        lk.layer = tile_layer_in_slot(TILE_LAYER_COARSE, layer->id);
        tile_view c, b, l;
        if (tile_cache_acquire(w->cache, ck, &c, err) != 0) {
            rc = -1;
            break;
        }
        if (tile_cache_acquire(w->cache, bk, &b, err) != 0) {
            tile_cache_release(w->cache, &c);
            rc = -1;
            break;
        }
        if (tile_cache_acquire_write(w->cache, lk, &l, err) == 0) {
            const float *cf = c.data, *bf = b.data;
            float *lf = l.data;
            for (size_t k = 0; k < TILE_SAMPLES; k++)
                lf[k] = layer_blend_solve(LAYER_BLEND_ADD, 1.0f, bf[k], NAN, cf[k]);
            tile_cache_release(w->cache, &l);
        } else {
            rc = -1;
        }
        tile_cache_release(w->cache, &b);
        tile_cache_release(w->cache, &c);
    }
    free(keys);
    return rc;
}

// Material tiles of every slot at level 0 (the count rides in element 0).
static int collect_paint(void *user, tile_key key) {
    tile_key **keys = user;
    if (tile_key_kind(key) != TILE_LAYER_MATERIAL || key.level != 0) return 0;
    size_t n = (size_t)(*keys)[0].tx;
    tile_key *grown = realloc(*keys, (n + 2) * sizeof **keys);
    if (!grown) return 1;
    grown[n + 1] = key;
    grown[0].tx = (int32_t)(n + 1);
    *keys = grown;
    return 0;
}

static int same_place(const void *a, const void *b) {
    const tile_key *x = a, *y = b;
    if (x->face != y->face) return x->face < y->face ? -1 : 1;
    if (x->ty != y->ty) return x->ty < y->ty ? -1 : 1;
    if (x->tx != y->tx) return x->tx < y->tx ? -1 : 1;
    return (x->layer > y->layer) - (x->layer < y->layer);
}

// Paint from before paint layers lives only in the composite's material tiles: where no
// base or paint layer tile sits under a composite one, the composite is the ground's own
// paint (the base, slot 1), so recomposing keeps it. A composite made from layers always
// has a layer or base tile under it, so this adopts nothing twice.
static int adopt_paint_as_base(world *w, og_error *err) {
    tile_key *keys = calloc(1, sizeof *keys);
    if (!keys) return og_error_set(err, "out of memory");
    if (tile_store_each(w->store, collect_paint, &keys, err) != 0) {
        free(keys);
        return -1;
    }
    size_t n = (size_t)keys[0].tx;
    qsort(keys + 1, n, sizeof *keys, same_place);
    int rc = 0;
    for (size_t i = 1; i <= n && rc == 0; i++) {
        tile_key ck = keys[i];
        if (tile_key_slot(ck) != 0) continue;
        // Sorted by place then slot: the slot-0 tile comes first at its place.
        if (i < n && keys[i + 1].face == ck.face && keys[i + 1].tx == ck.tx &&
            keys[i + 1].ty == ck.ty)
            continue;
        tile_key bk = ck;
        bk.layer = tile_layer_in_slot(TILE_LAYER_MATERIAL, TILE_SLOT_BASE);
        tile_view c, b;
        if (tile_cache_acquire(w->cache, ck, &c, err) != 0) {
            rc = -1;
            break;
        }
        if (tile_cache_acquire_write(w->cache, bk, &b, err) == 0) {
            memcpy(b.data, c.data, tile_layer_bytes(TILE_LAYER_MATERIAL));
            tile_cache_release(w->cache, &b);
        } else {
            rc = -1;
        }
        tile_cache_release(w->cache, &c);
    }
    free(keys);
    return rc;
}

world *world_load(const char *path, const world_settings *settings, int *errors, og_error *err) {
    world_params p;
    int errs = 0;
    load_report report = {.settings = settings, .path_len = strlen(path)};
    char cut_short[1200];
    if (world_params_load_whole(path, &p, &errs, collect_report, &report, cut_short,
                                sizeof cut_short, err) != 0)
        return NULL;
    if (errors) *errors = errs;
    if (check_params(&p, err) != 0) {
        char msg[sizeof err->msg + 4200];
        snprintf(msg, sizeof msg, "%s: error: %s", path, err->msg);
        size_t n = strlen(msg) < sizeof err->msg - 1 ? strlen(msg) : sizeof err->msg - 1;
        memcpy(err->msg, msg, n);
        err->msg[n] = 0;
        return NULL;
    }
    char tiles[4096];
    if (world_params_tiles_path(&p, path, tiles, sizeof tiles, err) != 0) return NULL;
    int before_layers = p.layers.count == 0;
    world *w = world_alloc(&p, settings);
    if (!w) {
        og_error_set(err, "out of memory");
        return NULL;
    }
    snprintf(w->path, sizeof w->path, "%s", path);
    w->file_errors = errs;
    memcpy(w->file_problems, report.problems, sizeof w->file_problems);
    // Loading never creates files: a world with no tile store yet has only its journal.
    int failed = open_journal(w, err) != 0;
    if (!failed) failed = open_checked_store(w, tiles, err) != 0;
    if (!failed && cut_short[0]) // its missing keys became defaults: never adopted
        snprintf(w->read_only, sizeof w->read_only,
                 "the file is %s; opened read-only (save to another file keeps your edits; "
                 "'save force=1' writes a whole file over it)",
                 cut_short);
    long owner = 0;
    int locked = failed ? -1 : lock_files(w, tiles, &owner, err);
    if (locked < 0 || start_cache(w, err) != 0 ||
        (before_layers && w->store && adopt_edits_as_layer(w, err) != 0) ||
        (w->store && adopt_paint_as_base(w, err) != 0)) {
        world_close(w);
        return NULL;
    }
    if (locked == 1) {
        // Edits stay possible in memory; only saving over its files is refused.
        w->open_in = owner ? owner : -1;
        snprintf(w->read_only, sizeof w->read_only,
                 "it is open in process %ld; save to another file to keep your edits", owner);
        warn_path(w, path, "warning: %s is open in process %ld: opened read-only", path, owner);
    }
    if (!w->read_only[0]) find_recoverable(w);
    if (w->read_only[0] && !w->open_in) {
        warn_path(w, path, "error: %s", w->read_only);
        if (errors) ++*errors;
    }
    return w;
}

void world_close(world *w) {
    if (!w) return;
    // The cache's dirty tiles would go to the scratch store, removed just below: unsaved
    // edits live on in the crash journal, not there (writing back an 8192^2 import cost
    // seconds at every exit).
    tile_cache_destroy_discarding(w->cache);
    free(w->gen);
    w->cache = NULL;
    w->gen = NULL;
    // The journal stays: only a save of its edits or 'recover discard' removes it, or
    // the successful end of a script that began it (world_settings.scripted): the script
    // is the record of those edits, and each run on a saved world would otherwise set
    // the last one aside. A failed script (a save on a full disk) keeps it. A journal
    // this session began whose edits were all undone holds nothing unsaved: it goes too
    // (else the next start offers to recover nothing).
    int nothing_unsaved = w->rj && !history_modified(w->history);
    recovery_journal_close(w->rj);
    w->rj = NULL; // the history's end below waits for it no more
    if ((w->settings.scripted || nothing_unsaved) && w->journal_fresh && !w->keep_journal &&
        w->recover_path[0])
        unlink(w->recover_path);
    close_stores(w);
    file_lock_release(&w->lock);
    history_destroy(w->history);
    world_events_release(w->own_events);
    free(w->base_source);
    free(w);
}

// 128 random bits as 32 lowercase hex digits (world ids and saved-state ids).
static int new_world_id(char out[WORLD_ID_CHARS + 1], og_error *err) {
    unsigned char bits[WORLD_ID_CHARS / 2];
    size_t got = 0;
    while (got < sizeof bits) {
        ssize_t n = getrandom(bits + got, sizeof bits - got, 0);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) return og_error_set(err, "save: cannot make a world id: %s", strerror(errno));
        got += (size_t)n;
    }
    for (size_t i = 0; i < sizeof bits; i++)
        snprintf(out + 2 * i, 3, "%02x", bits[i]);
    return 0;
}

// Whether saving to path would destroy something the user made that this world does
// not hold: the lines its own file had errors on, or a file that is not ours.
static int check_overwrite(const world *w, const char *path, og_error *err) {
    if (strcmp(path, w->path) == 0) {
        if (w->read_only[0] && !w->open_in) // the lock is checked again when saving
            return og_error_set(err, "save: %s was opened read-only: %s", path, w->read_only);
        if (!w->file_errors) return 0;
        // One line: "2: error: ...; 5: error: ...".
        char problems[2 * sizeof w->file_problems];
        size_t n = 0;
        for (const char *c = w->file_problems; *c; c++) {
            if (*c == '\n')
                problems[n++] = ';', problems[n++] = ' ';
            else
                problems[n++] = *c;
        }
        problems[n] = 0;
        return og_error_set(err,
                            "save: %s had %d error%s when loaded (%s); saving would write the "
                            "defaults over %s. Fix the file, save to another file, or 'save %s "
                            "force=1' to replace it",
                            path, w->file_errors, w->file_errors == 1 ? "" : "s", problems,
                            w->file_errors == 1 ? "that line" : "those lines", path);
    }
    if (access(path, F_OK) != 0) return 0;
    og_error why;
    if (world_params_check_file(path, &why) == 0) return 0;
    return og_error_set(err, "save: will not replace %s: %s. 'save %s force=1' replaces it", path,
                        why.msg, path);
}

typedef struct orphans {
    const layer_table *table;
    tile_store_write *writes;
    size_t count, cap;
    int oom;
} orphans;

// A tile of a layer no longer in the table (its id or its painted mask's slot).
static int collect_orphan(void *user, tile_key key) {
    orphans *o = user;
    int32_t slot = tile_key_slot(key);
    if (slot < LAYER_FIRST_ID) return 0;
    int32_t id = slot > LAYER_ID_MAX ? slot - LAYER_ID_MAX - 1 : slot;
    if (layer_table_find_id(o->table, id) >= 0) return 0;
    if (o->count == o->cap) {
        size_t cap = o->cap ? o->cap * 2 : 64;
        tile_store_write *grown = realloc(o->writes, cap * sizeof *grown);
        if (!grown) return o->oom = 1;
        o->writes = grown;
        o->cap = cap;
    }
    o->writes[o->count++] = (tile_store_write){key, NULL};
    return 0;
}

// Deleted and merged layers leave their tiles empty (the undo history holds what they
// were, and an empty tile is what a missing one generates): the saved store drops them.
static int drop_removed_layers(tile_store *target, const layer_table *t, og_error *err) {
    orphans o = {.table = t};
    int rc = tile_store_each(target, collect_orphan, &o, err);
    if (rc == 0 && o.oom) rc = og_error_set(err, "out of memory saving");
    if (rc == 0 && o.count) rc = tile_store_put_batch(target, o.writes, o.count, err);
    free(o.writes);
    return rc;
}

// Writes the world's files at path (tiles beside it) once world_save has checked
// that it may; on failure the world keeps working as before.
static int save_files(world *w, const char *path, world_params p, const char *tiles,
                      og_error *err) {
    if (tile_cache_flush(w->cache, err) != 0) return -1;

    int same_store = w->store && strcmp(tiles, tile_store_path(w->store)) == 0;
    tile_store *target = same_store ? w->store : tile_store_open(tiles, err);
    if (!target) return -1;
    // A new place gets the saved tiles (and loses those of whatever was saved there
    // before), then the journal's edits: all in one transaction, with the saved state's id.
    const char *sources[2];
    size_t count = 0;
    if (!same_store && w->store) sources[count++] = tile_store_path(w->store);
    sources[count++] = tile_store_path(w->journal);
    char state_id[WORLD_ID_CHARS + 1];
    int rc = new_world_id(state_id, err);
    if (rc == 0) rc = tile_store_merge_from(target, sources, count, !same_store, state_id, err);
    if (rc == 0) rc = drop_removed_layers(target, &p.layers, err);
    // The world's id goes into the store and, with its tile count, into the file, so
    // a store that later goes missing, empty or is swapped is noticed on load.
    if (rc == 0 && !p.tiles_id[0]) rc = new_world_id(p.tiles_id, err);
    if (rc == 0) rc = tile_store_set_meta(target, "world_id", p.tiles_id, err);
    if (rc == 0) p.tiles_saved = tile_store_count(target, -1);
    if (rc == 0) rc = world_params_save(path, &p, err);
    if (rc != 0) {
        if (!same_store) tile_store_close(target);
        return -1;
    }
    // A new store: the cache that reads it must run before the old one stops, so a
    // failure here leaves the world as it was (the files are written; saving again
    // is harmless).
    tile_cache *cache = NULL;
    world_generation *gen = NULL;
    if (!same_store && make_cache(w, &w->params, target, &cache, &gen, err) != 0) {
        tile_store_close(target);
        return -1;
    }
    // Everything is in the saved files now; a failure to empty the journal only
    // costs space (its tiles equal the saved ones).
    og_error ignored;
    tile_store_clear(w->journal, &ignored);
    history_mark_saved(w->history);
    w->params = p;
    snprintf(w->path, sizeof w->path, "%s", path);
    w->file_errors = 0;
    w->file_problems[0] = 0;
    w->read_only[0] = 0;
    // The saved files hold this session's edits now: its journal is done with. Another
    // session's, unrecovered, stays (its edits are not saved); the next edit starts a
    // journal on the new state.
    if (w->rj) unlink(w->recover_path);
    recovery_journal_close(w->rj);
    w->rj = NULL;
    memcpy(w->state_id, state_id, sizeof w->state_id);
    snprintf(w->recover_path, sizeof w->recover_path, "%s.recover", path);
    w->unsaved_journal = 0;
    w->recoverable = 0;
    w->journal_failed = 0;
    if (!same_store) {
        swap_cache(w, cache, gen);
        tile_store_close(w->store);
        w->store = target;
    }
    return 0;
}

int world_save(world *w, const char *path, int force, og_error *err) {
    // A copy: w->path is rewritten below, and snprintf from a buffer into itself is undefined
    // (a bare `save` left the world with no path).
    char target_path[sizeof w->path];
    snprintf(target_path, sizeof target_path, "%s", path && *path ? path : w->path);
    path = target_path;
    if (!*path) return og_error_set(err, "save: this world has no file yet; give a file name");
    if (!force && check_overwrite(w, path, err) != 0) return -1;
    world_params p = w->params;
    char tiles[4096];
    if (strcmp(path, w->path) != 0) p.tiles[0] = 0; // a new file gets its own NAME.tiles
    if (world_params_tiles_path(&p, path, tiles, sizeof tiles, err) != 0) return -1;
    // A file its owner made read-only is protected, also from root (rename would
    // replace it whatever its mode).
    struct stat st;
    if (stat(path, &st) == 0 && S_ISREG(st.st_mode) && !(st.st_mode & 0222))
        return og_error_set(
            err, "save: %s is read-only (no write permission); save to another file", path);
    if (stat(tiles, &st) == 0 && S_ISREG(st.st_mode) && !(st.st_mode & 0222))
        return og_error_set(
            err, "save: its tile store %s is read-only (no write permission); save to another file",
            tiles);
    // One writer: files another live process has open are not written, even forced.
    char lock_path[4300];
    lock_path_of(tiles, lock_path, sizeof lock_path);
    file_lock lock = {.fd = -1};
    if (w->lock.fd < 0 || strcmp(w->lock.path, lock_path) != 0) {
        long owner = 0, stale = 0;
        file_lock_result r = file_lock_acquire(&lock, lock_path, &owner, &stale, err);
        if (r == FILE_LOCK_ERROR) return -1;
        if (r == FILE_LOCK_REFUSED) {
            og_error why = *err;
            return og_error_set(err, "save: %s", why.msg);
        }
        if (r == FILE_LOCK_HELD)
            return og_error_set(err, "save: %s is open in process %ld; save to another file", path,
                                owner);
    }
    if (save_files(w, path, p, tiles, err) != 0) {
        file_lock_release(&lock);
        return -1;
    }
    if (lock.fd >= 0) {
        file_lock_release(&w->lock);
        w->lock = lock;
    }
    w->open_in = 0;
    world_publish(w, &(world_event){.kind = WORLD_EVENT_SAVED});
    return 0;
}

// Whether two parameter sets generate the same terrain (they may differ in layers).
static int same_generation(const world_params *a, const world_params *b) {
    world_params x = *a, y = *b;
    memset(&x.layers, 0, sizeof x.layers);
    memset(&y.layers, 0, sizeof y.layers);
    // Where the world lies on the Earth does not change its terrain either.
    memset(x.geo_transform, 0, sizeof x.geo_transform);
    memset(y.geo_transform, 0, sizeof y.geo_transform);
    x.geo_crs[0] = y.geo_crs[0] = 0;
    char *tx = world_params_format(&x), *ty = world_params_format(&y);
    int same = tx && ty && !strcmp(tx, ty);
    free(tx);
    free(ty);
    return same;
}

int world_regenerate(world *w, const world_params *params, og_error *err) {
    if (check_params(params, err) != 0) return -1;
    world_params next = *params;
    // The file-level settings that are not generation parameters stay the world's own.
    snprintf(next.tiles, sizeof next.tiles, "%s", w->params.tiles);
    memcpy(next.tiles_id, w->params.tiles_id, sizeof next.tiles_id);
    next.tiles_saved = w->params.tiles_saved;
    next.material_rules = w->params.material_rules; // the look: world_set_material_rules
    if (!next.layers.count) next.layers = w->params.layers;
    // Only the layer table or the georeference changed (a layer command, an import
    // giving the world its place, their undo): the terrain generates the same, so the
    // cache stays.
    if (same_generation(&next, &w->params)) {
        w->params = next;
        world_publish(w, &(world_event){.kind = WORLD_EVENT_LAYERS});
        return 0;
    }
    // Edited tiles must reach the journal before a new cache reads it; the old cache
    // keeps running until the new one does.
    tile_cache *cache = NULL;
    world_generation *gen = NULL;
    if (tile_cache_flush(w->cache, err) != 0 ||
        make_cache(w, &next, w->store, &cache, &gen, err) != 0)
        return -1;
    swap_cache(w, cache, gen);
    w->params = next;
    world_publish(w, &(world_event){.kind = WORLD_EVENT_PARAMS});
    return 0;
}

void world_set_material_rules(world *w, const material_rules *rules) {
    w->params.material_rules = *rules;
    w->params.material_rules.implicit = 0;
}

const world_params *world_get_params(const world *w) {
    return &w->params;
}

const char *world_path(const world *w) {
    return w->path;
}
tile_cache *world_cache(world *w) {
    return w->cache;
}
tile_store *world_store(world *w) {
    return w->store;
}
tile_store *world_journal(world *w) {
    return w->journal;
}
history *world_history(world *w) {
    return w->history;
}
world_events *world_event_hub(world *w) {
    return w->settings.events;
}
void world_publish(world *w, const world_event *e) {
    world_events_publish(w->settings.events, e);
}
void world_publish_area(world *w, tile_layer layer, int face, grid_rect r) {
    world_publish(
        w, &(world_event){.kind = WORLD_EVENT_AREA, .layer = layer, .face = face, .rect = r});
}
int world_is_modified(const world *w) {
    return history_modified(w->history);
}
void world_warn(const world *w, const char *message) {
    w->settings.warn(w->settings.warn_user, message);
}

// Level-0 samples along X and Z, or 0 when unbounded.
static int64_t world_extent(const world *w, int64_t *along_z) {
    if (w->params.kind == WORLD_PLANET) return *along_z = world_grid_face_samples(&w->params);
    *along_z = world_params_size_z(&w->params);
    return w->params.size;
}

static int check_face(const world *w, int face, og_error *err) {
    int faces = w->params.kind == WORLD_PLANET ? 6 : 1;
    if (face < 0 || face >= faces)
        return og_error_set(err, "face %d does not exist (this world has %s)", face,
                            faces == 6 ? "faces 0-5" : "only face 0");
    return 0;
}

static int read_sample(world *w, int face, int64_t gx, int64_t gz, float *out, og_error *err) {
    tile_key key = {TILE_LAYER_COARSE, face, 0, (int32_t)world_grid_floor_div(gx, TILE_SIZE),
                    (int32_t)world_grid_floor_div(gz, TILE_SIZE)};
    tile_view v;
    if (tile_cache_acquire(w->cache, key, &v, err) != 0) return -1;
    int64_t i = gx - (int64_t)key.tx * TILE_SIZE, j = gz - (int64_t)key.ty * TILE_SIZE;
    *out = ((const float *)v.data)[j * TILE_SIZE + i];
    tile_cache_release(w->cache, &v);
    return 0;
}

// Samples addressable at all: int32 tile coordinates.
static int in_tile_range(double index) {
    return fabs(index) < (double)INT32_MAX * TILE_SIZE - 2.0;
}

int world_sample(world *w, int face, double x, double z, double *height, og_error *err) {
    if (check_face(w, face, err) != 0) return -1;
    if (!isfinite(x) || !isfinite(z)) return og_error_set(err, "position must be finite numbers");
    const double sp = world_grid_sample_metres(&w->params); // true metres on a planet
    double fx = x / sp, fz = z / sp;
    int64_t nz, n = world_extent(w, &nz);
    // An edge's position as printed (rounded, and read back) may land a little past it:
    // up to a thousandth of a sample counts as the edge.
    const double slack = 1e-3;
    if (n > 0 && fx > (double)(n - 1) && fx < (double)(n - 1) + slack) fx = (double)(n - 1);
    if (n > 0 && fz > (double)(nz - 1) && fz < (double)(nz - 1) + slack) fz = (double)(nz - 1);
    if (n > 0 && fx < 0 && fx > -slack) fx = 0;
    if (n > 0 && fz < 0 && fz > -slack) fz = 0;
    if (n > 0 && (fx < 0 || fz < 0 || fx > (double)(n - 1) || fz > (double)(nz - 1)))
        return og_error_set(err,
                            "position (%.10g, %.10g) m lies outside the world (0 to %.10g m, 0 to "
                            "%.10g m)",
                            x, z, (double)(n - 1) * sp, (double)(nz - 1) * sp);
    if (!in_tile_range(fx) || !in_tile_range(fz))
        return og_error_set(err, "position (%g, %g) m lies beyond the int32 tile range", x, z);
    int64_t i0 = (int64_t)floor(fx), j0 = (int64_t)floor(fz);
    double tx = fx - (double)i0, tz = fz - (double)j0;
    // Neighbours are read only when they carry weight, so the last row and column
    // of a bounded world need nothing beyond it.
    float h00, h10 = 0, h01 = 0, h11 = 0;
    if (read_sample(w, face, i0, j0, &h00, err) != 0) return -1;
    if (tx > 0 && read_sample(w, face, i0 + 1, j0, &h10, err) != 0) return -1;
    if (tz > 0 && read_sample(w, face, i0, j0 + 1, &h01, err) != 0) return -1;
    if (tx > 0 && tz > 0 && read_sample(w, face, i0 + 1, j0 + 1, &h11, err) != 0) return -1;
    double top = h00 + (h10 - h00) * tx, bottom = h01 + (h11 - h01) * tx;
    *height = tz > 0 ? top + (bottom - top) * tz : top;
    return 0;
}

#define HASH_PREFETCH 6 // tiles queued ahead so both workers stay busy

int world_hash(world *w, int face, double x0, double z0, double x1, double z1, uint64_t *digest,
               uint64_t *count, og_error *err) {
    if (check_face(w, face, err) != 0) return -1;
    if (!isfinite(x0) || !isfinite(z0) || !isfinite(x1) || !isfinite(z1))
        return og_error_set(err, "rectangle corners must be finite numbers");
    if (x1 < x0 || z1 < z0)
        return og_error_set(err, "rectangle is empty: need X0 <= X1 and Z0 <= Z1");
    double sp = world_grid_sample_metres(&w->params);
    double fx0 = ceil(x0 / sp), fz0 = ceil(z0 / sp), fx1 = floor(x1 / sp), fz1 = floor(z1 / sp);
    int64_t nz, n = world_extent(w, &nz);
    if (n > 0 && (fx0 < 0 || fz0 < 0 || fx1 > (double)(n - 1) || fz1 > (double)(nz - 1)))
        return og_error_set(err, "rectangle extends outside the world (0 to %g m, 0 to %g m)",
                            (double)(n - 1) * sp, (double)(nz - 1) * sp);
    if (!in_tile_range(fx0) || !in_tile_range(fz0) || !in_tile_range(fx1) || !in_tile_range(fz1))
        return og_error_set(err, "rectangle lies beyond the int32 tile range");
    int64_t gx0 = (int64_t)fx0, gz0 = (int64_t)fz0, gx1 = (int64_t)fx1, gz1 = (int64_t)fz1;
    uint64_t h = 0xcbf29ce484222325ULL, samples = 0;
    if (gx1 < gx0 || gz1 < gz0) {
        *digest = h;
        *count = 0;
        return 0;
    }
    // A typo in a corner should not start an hour-long walk: 2^32 samples (65536^2,
    // 16 GiB of heights) is far beyond any interactive check.
    double area = ((double)gx1 - (double)gx0 + 1) * ((double)gz1 - (double)gz0 + 1);
    if (area > 4294967296.0)
        return og_error_set(err,
                            "rectangle holds %.4g samples; at most 2^32 (65536 x 65536) "
                            "are hashed at once",
                            area);
    int64_t tx0 = world_grid_floor_div(gx0, TILE_SIZE), tx1 = world_grid_floor_div(gx1, TILE_SIZE);
    int64_t tz0 = world_grid_floor_div(gz0, TILE_SIZE), tz1 = world_grid_floor_div(gz1, TILE_SIZE);
    int64_t across = tx1 - tx0 + 1, total = across * (tz1 - tz0 + 1);
    for (int64_t t = 0; t < total; t++) {
        // Queue the next few tiles so the workers generate them while we hash this one.
        for (int64_t a = t + HASH_PREFETCH; a > t; a--) {
            if (a >= total) continue;
            tile_key ahead = {TILE_LAYER_COARSE, face, 0, (int32_t)(tx0 + a % across),
                              (int32_t)(tz0 + a / across)};
            tile_view v;
            tile_cache_request(w->cache, ahead, &v);
            tile_cache_release(w->cache, &v);
        }
        tile_key key = {TILE_LAYER_COARSE, face, 0, (int32_t)(tx0 + t % across),
                        (int32_t)(tz0 + t / across)};
        tile_view v;
        if (tile_cache_acquire(w->cache, key, &v, err) != 0) return -1;
        const uint32_t *bits = v.data;
        int64_t bx = (int64_t)key.tx * TILE_SIZE, bz = (int64_t)key.ty * TILE_SIZE;
        int i0 = (int)(gx0 > bx ? gx0 - bx : 0),
            i1 = (int)(gx1 < bx + TILE_SIZE - 1 ? gx1 - bx : TILE_SIZE - 1);
        int j0 = (int)(gz0 > bz ? gz0 - bz : 0),
            j1 = (int)(gz1 < bz + TILE_SIZE - 1 ? gz1 - bz : TILE_SIZE - 1);
        for (int j = j0; j <= j1; j++)
            for (int i = i0; i <= i1; i++) {
                // FNV-1a over 32-bit words: the float bit patterns, as stored.
                h ^= bits[j * TILE_SIZE + i];
                h *= 0x100000001b3ULL;
            }
        samples += (uint64_t)(i1 - i0 + 1) * (uint64_t)(j1 - j0 + 1);
        tile_cache_release(w->cache, &v);
    }
    *digest = h;
    *count = samples;
    return 0;
}

int world_file_errors(const world *w) {
    return w->file_errors;
}
const char *world_file_problems(const world *w) {
    return w->file_problems;
}
const char *world_read_only(const world *w) {
    return w->read_only;
}

int world_recovery_dir(char *out, size_t len, og_error *err) {
    const char *env = getenv("OROGEN_RECOVER_DIR"), *state = getenv("XDG_STATE_HOME"),
               *home = getenv("HOME");
    if (env && *env)
        snprintf(out, len, "%s", env);
    else if (state && *state)
        snprintf(out, len, "%s/orogen/recover", state);
    else if (home && *home)
        snprintf(out, len, "%s/.local/state/orogen/recover", home);
    else
        return og_error_set(err, "no folder for recovery journals ($HOME is not set)");
    // mkdir -p
    for (char *c = out + 1;; c++) {
        if (*c != '/' && *c) continue;
        char keep = *c;
        *c = 0;
        int rc = mkdir(out, 0700);
        int e = errno;
        *c = keep;
        if (rc != 0 && e != EEXIST)
            return og_error_set(err, "cannot create the recovery folder %s: %s", out, strerror(e));
        if (!keep) return 0;
    }
}

// A journal of this process for a never-saved world.
static int unsaved_journal_path(char *out, size_t len, og_error *err) {
    static unsigned counter;
    char dir[4096];
    if (world_recovery_dir(dir, sizeof dir, err) != 0) return -1;
    snprintf(out, len, "%s/unsaved-%ld-%lld-%u.recover", dir, (long)getpid(), (long long)time(NULL),
             counter++);
    return 0;
}

void world_journal_record(world *w, recovery_kind kind, const history_step *s) {
    if (w->journal_paused || w->read_only[0] || w->journal_failed) return;
    og_error err;
    if (!w->recover_path[0]) {
        if (w->path[0]) return;
        if (unsaved_journal_path(w->recover_path, sizeof w->recover_path, &err) != 0) {
            w->journal_failed = 1;
            warn_path(w, "unsaved world", "warning: %s; edits are not protected against a crash",
                      err.msg);
            return;
        }
        w->unsaved_journal = 1;
    }
    if (!w->rj) {
        struct stat st;
        if (!w->unsaved_journal && lstat(w->recover_path, &st) == 0) {
            // A new session's edits cannot follow another session's journal: it is set
            // aside under a free name (never overwritten; 'recover list' shows it).
            char aside[4400];
            if (journal_files_set_aside(w->recover_path, aside, sizeof aside, &err) != 0) {
                w->journal_failed = 1;
                warn_path(w, w->path,
                          "warning: %s; it stays as it is, and this session's edits are not "
                          "journaled (not protected against a crash)",
                          err.msg);
                return;
            }
            warn_path(w, w->path,
                      "warning: the unrecovered journal of an earlier session was set aside as "
                      "%s ('recover list' lists it, 'recover %s' restores it)",
                      aside, aside);
            w->recoverable = 0;
        }
        if (!(w->rj = recovery_journal_open(w->recover_path, w->state_id,
                                            w->unsaved_journal ? &w->base_params : NULL,
                                            w->unsaved_journal ? w->base_source : NULL, 0, &err))) {
            w->journal_failed = 1;
            warn_path(w, w->path[0] ? w->path : "unsaved world",
                      "warning: %s; edits are not protected against a crash", err.msg);
            return;
        }
        w->journal_fresh = 1;
    }
    if (recovery_journal_append(w->rj, kind, s, &err) != 0) {
        w->journal_failed = 1;
        warn_path(w, w->path[0] ? w->path : "unsaved world",
                  "warning: %s; edits are not protected against a crash", err.msg);
    }
}

void world_journal_wait(const world *w) {
    og_error ignored; // a failed write is reported by the next record's append
    recovery_journal_wait(w->rj, &ignored);
}

void world_keep_journal(world *w) {
    w->keep_journal = 1;
}

int world_session_journaled(const world *w) {
    return w->rj != NULL;
}

size_t world_recoverable(const world *w, int64_t *when) {
    if (when) *when = w->recoverable_when;
    return w->recoverable;
}

const char *world_recovery_path(const world *w) {
    return w->recover_path;
}

const char *world_state_id(const world *w) {
    return w->state_id;
}

void world_journal_pause(world *w, int paused) {
    w->journal_paused = paused;
}

int world_set_base_source(world *w, const char *source, og_error *err) {
    char *copy = source && *source ? strdup(source) : NULL;
    if (source && *source && !copy) return og_error_set(err, "out of memory");
    free(w->base_source);
    w->base_source = copy;
    return 0;
}

int world_journal_continue(world *w, const char *journal, size_t keep_bytes, og_error *err) {
    w->recoverable = 0;
    w->journal_fresh = 0; // another session's edits: never removed but by save or discard
    if (w->read_only[0]) return 0;
    recovery_journal_close(w->rj);
    w->rj = NULL;
    if (journal && journal != w->recover_path)
        snprintf(w->recover_path, sizeof w->recover_path, "%s", journal);
    w->rj = recovery_journal_open(w->recover_path, w->state_id,
                                  w->unsaved_journal ? &w->base_params : NULL,
                                  w->unsaved_journal ? w->base_source : NULL, keep_bytes, err);
    return w->rj ? 0 : -1;
}

int world_adopt_journal(world *w, const char *journal, size_t keep_bytes, og_error *err) {
    if (unsaved_journal_path(w->recover_path, sizeof w->recover_path, err) != 0) return -1;
    if (rename(journal, w->recover_path) != 0)
        return og_error_set(err, "recover: cannot take over %s: %s", journal, strerror(errno));
    w->unsaved_journal = 1;
    return world_journal_continue(w, NULL, keep_bytes, err);
}

int world_recover_discard(world *w, og_error *err) {
    if (!w->recover_path[0] || (access(w->recover_path, F_OK) != 0 && !w->rj))
        return og_error_set(err, "recover: %s has no recovery journal",
                            w->path[0] ? w->path : "this world");
    if (w->rj) recovery_journal_close(w->rj);
    w->rj = NULL;
    w->recoverable = 0;
    if (unlink(w->recover_path) != 0 && errno != ENOENT)
        return og_error_set(err, "recover: cannot remove %s: %s", w->recover_path, strerror(errno));
    return 0;
}
