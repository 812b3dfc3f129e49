#include "editor/cmd/interchange_commands.h"

#include "editor/cmd/base_pending.h"
#include "editor/interchange/export.h"
#include "editor/interchange/export_planet.h"
#include "editor/interchange/export_vdb.h"
#include "editor/interchange/import.h"
#include "editor/params/world_georef.h"
#include "io/crc32c.h"
#include "io/parse.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <stdio.h>
#include <time.h>

static double seconds_since(const struct timespec *t0) {
    struct timespec t1;
    clock_gettime(CLOCK_MONOTONIC, &t1);
    return (double)(t1.tv_sec - t0->tv_sec) + (double)(t1.tv_nsec - t0->tv_nsec) * 1e-9;
}

static int parse_import_options(int argc, char **argv, int first, import_options *o,
                                og_error *err) {
    import_options_defaults(o);
    for (int i = first; i < argc; i++) {
        char buf[512], *key, *value;
        if (parse_setting(argv[i], buf, sizeof buf, &key, &value, err) != 0 ||
            import_options_set(o, key, value, err) != 0)
            return -1;
    }
    return 0;
}

static void print_import(FILE *out, const char *path, const import_report *r, tile_layer layer,
                         double seconds) {
    fprintf(out,
            "imported %s: %d x %d samples (%s), %.6g x %.6g m apart; heights %.6g .. %.6g m "
            "(%s); %lld voids filled; placed at %.6g, %.6g .. %.6g, %.6g m on the %s layer "
            "(%lld samples); %.2f s\n",
            path, r->width, r->height, r->source, r->spacing_x, r->spacing_z, r->min, r->max,
            r->mapping, (long long)r->voids, r->x0, r->z0, r->x1, r->z1,
            layer == TILE_LAYER_DETAIL ? "detail" : "coarse", (long long)r->samples, seconds);
    if (r->adopted_georef)
        fprintf(out, "the world takes the file's place on the Earth (its coordinate system and "
                     "geotransform; undo gives it back)\n");
}

int cmd_import(cmd_context *ctx, int argc, char **argv, og_error *err) {
    import_options o;
    if (parse_import_options(argc, argv, 2, &o, err) != 0) return -1;
    struct timespec t0;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    import_report r;
    if (import_apply(ctx->world, argv[1], &o, &r, err) != 0) return -1;
    print_import(ctx->out, argv[1], &r, o.layer, seconds_since(&t0));
    if (o.edit_layer[0]) { // the layer it went into (layer=new named it after the file)
        const layer_table *t = &world_get_params(ctx->world)->layers;
        fprintf(ctx->out, "into layer %s\n", t->layers[t->active].name);
    }
    return 0;
}

// CRC32C of the mapped samples: a remade base is checked to be the one made.
static uint32_t samples_crc(const raster *r) {
    return crc32c_update(0, r->samples, sizeof(float) * (size_t)r->width * (size_t)r->height);
}

// Imports src at the corner of a world made for it, one world sample per raster sample,
// as the world's base: not journaled (its journal names the file instead, source).
static int place_base(world *w, const char *path, import_source *src, import_options *o,
                      const char *source, import_report *rep, og_error *err) {
    const world_params *p = world_get_params(w);
    o->has_position = 1;
    o->x = o->z = 0;
    o->anchor_centre = 0;
    o->starting_state = 1; // the world is the raster: undo has no flat world to go back to
    src->spacing_x = src->spacing_z = p->spacing;
    if (world_set_base_source(w, source, err) != 0) return -1;
    world_journal_pause(w, source != NULL);
    int rc = import_apply_source(w, path, src, o, rep, err);
    world_journal_pause(w, 0);
    return rc;
}

// What a world's journal keeps of the raster it was made from: its absolute path, the
// import options, one a line, and its size and samples' checksum. NULL when the path
// cannot be kept so (the journal then holds the samples, as for any edit).
static char *base_source_text(const char *path, int argc, char **argv, int first, const raster *r) {
    char real[PATH_MAX];
    if (!realpath(path, real) || strchr(real, '\n')) return NULL;
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    if (!f) return NULL;
    fprintf(f, "raster %s\n", real);
    for (int i = first; i < argc; i++)
        if (!strchr(argv[i], '\n')) fprintf(f, "%s\n", argv[i]);
    fprintf(f, "samples %d x %d crc32c %08x\n", r->width, r->height, samples_crc(r));
    fclose(f);
    if (text && len >= RECOVERY_SOURCE_MAX) free(text), text = NULL;
    return text;
}

world *cmd_world_from_raster(cmd_context *ctx, const char *path, int argc, char **argv, int first,
                             struct base_pending **pending_out, og_error *err) {
    *pending_out = NULL;
    import_options o;
    if (parse_import_options(argc, argv, first, &o, err) != 0) return NULL;
    if (o.layer != TILE_LAYER_COARSE || o.edit_layer[0]) {
        og_error_set(err, "new flat from=: the raster becomes the coarse layer (no layer=)");
        return NULL;
    }
    struct timespec t0;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    import_source src;
    if (import_source_read(path, &o, p.max_height, &src, err) != 0) return NULL;
    // The world is the raster: one coarse sample per raster sample, every row and
    // column, at one spacing. Rows and columns of a geographic DEM are different
    // distances apart (degrees of longitude shrink toward the poles): the world then
    // takes their geometric mean (areas kept) unless spacing= says.
    double sx = src.spacing_x, sz = src.spacing_z;
    if (sx <= 0) sx = sz = p.spacing;
    const int width = src.raster.width, height = src.raster.height;
    if (width < 2 || height < 2) {
        og_error_set(err, "%s: %d x %d samples: a world needs at least 2 x 2", path, width, height);
        import_source_free(&src);
        return NULL;
    }
    const double spacing = sx == sz ? sx : sqrt(sx * sz);
    p.generator = GEN_FLAT;
    p.base_height = src.min;
    p.max_height = fmax(1.0, fmax(fabs(src.min), fabs(src.max)));
    p.spacing = spacing;
    p.size = width;
    p.size_z = height == width ? 0 : height;
    // The source's place on the Earth, by sample: the world's coarse sample (column,
    // row) is the raster's.
    const gdal_georef *geo = &src.raster.georef;
    if (geo->geotransform[1] * geo->geotransform[5] - geo->geotransform[2] * geo->geotransform[4] !=
        0) {
        memcpy(p.geo_transform, geo->geotransform, sizeof p.geo_transform);
        snprintf(p.geo_crs, sizeof p.geo_crs, "%s", geo->crs);
    }
    world *w = world_params_validate(&p, err) == 0 ? world_create(&p, &ctx->settings, err) : NULL;
    char *source = w ? base_source_text(path, argc, argv, first, &src.raster) : NULL;
    import_report rep;
    // In a batch script the world imports its parts as they are needed (base_pending.h):
    // here only what the import reports, nothing written yet.
    base_pending *pending = NULL;
    o.has_limit = ctx->defer_base;
    if (w && place_base(w, path, &src, &o, source, &rep, err) != 0) {
        world_close(w);
        w = NULL;
    }
    if (w && ctx->defer_base) {
        o.has_limit = 0;
        pending = base_pending_new(w, path, &src, &o, source != NULL);
        if (!pending && place_base(w, path, &src, &o, source, &rep, err) != 0) {
            world_close(w); // no memory to keep it pending: imported whole, as without a script
            w = NULL;
        }
    }
    free(source);
    import_source_free(&src);
    if (!w) return NULL;
    *pending_out = pending;
    fprintf(ctx->out, "new flat world of %lld x %lld samples, %.6g m apart, from %s",
            (long long)p.size, (long long)world_params_size_z(&p), spacing, path);
    if (sx != sz)
        fprintf(ctx->out,
                " (its columns are %.6g m apart and its rows %.6g m: the world keeps every sample "
                "at their geometric mean; spacing= chooses)",
                sx, sz);
    if (world_georef_present(&p))
        fprintf(ctx->out, "; georeferenced%s%s", p.geo_crs[0] ? "" : " (no coordinate system)",
                p.geo_crs[0] ? " (the world file keeps its coordinate system and geotransform)"
                             : "");
    fprintf(ctx->out, "\n");
    print_import(ctx->out, path, &rep, TILE_LAYER_COARSE, seconds_since(&t0));
    return w;
}

int cmd_world_from_raster_again(world *w, const char *source, og_error *err) {
    char text[RECOVERY_SOURCE_MAX];
    snprintf(text, sizeof text, "%s", source);
    char *lines[256];
    int n = 0;
    for (char *save = NULL, *l = strtok_r(text, "\n", &save); l && n < 256;
         l = strtok_r(NULL, "\n", &save))
        lines[n++] = l;
    int width = 0, height = 0;
    unsigned crc = 0;
    if (n < 2 || strncmp(lines[0], "raster ", 7) != 0 ||
        sscanf(lines[n - 1], "samples %d x %d crc32c %x", &width, &height, &crc) != 3)
        return og_error_set(err, "its source is not described as Orogen writes it");
    const char *path = lines[0] + 7;
    // The options as given, for import's parser (argv[0] and argv[1] are the command's).
    char *argv[258] = {"new", "flat"};
    for (int i = 1; i < n - 1; i++)
        argv[i + 1] = lines[i];
    import_options o;
    if (parse_import_options(n, argv, 2, &o, err) != 0) return -1;
    world_params defaults;
    world_params_default(&defaults, WORLD_FLAT);
    import_source src;
    og_error why;
    if (import_source_read(path, &o, defaults.max_height, &src, &why) != 0)
        return og_error_set(err, "it was made from %s, which cannot be read now (%s)", path,
                            why.msg);
    int rc = 0;
    if (src.raster.width != width || src.raster.height != height || samples_crc(&src.raster) != crc)
        rc = og_error_set(err,
                          "it was made from %s, which has changed since (%d x %d samples, "
                          "checksum %08x; it was %d x %d, %08x): put the file back as it was "
                          "and recover again",
                          path, src.raster.width, src.raster.height, samples_crc(&src.raster),
                          width, height, crc);
    import_report rep;
    if (rc == 0) rc = place_base(w, path, &src, &o, NULL, &rep, err);
    import_source_free(&src);
    return rc;
}

// Seed 004's `export N FILE [size=PIXELS]` on planets.
static int export_planet_command(cmd_context *ctx, int argc, char **argv, og_error *err) {
    int64_t n = 0;
    if (parse_i64(argv[1], &n) != 0 || n > EXPORT_PLANET_MAX_SUBDIVISION)
        return og_error_set(err, "export N FILE: N is the cube's subdivision, 0 .. %d, got '%s'",
                            EXPORT_PLANET_MAX_SUBDIVISION, argv[1]);
    int64_t size = 0;
    for (int i = 3; i < argc; i++) {
        char buf[512], *key, *value;
        if (parse_setting(argv[i], buf, sizeof buf, &key, &value, err) != 0) return -1;
        if (strcmp(key, "size") != 0)
            return og_error_set(err, "export N FILE: unknown option '%s' (size=PIXELS)", key);
        if (parse_i64(value, &size) != 0 || size < 1 || size > EXPORT_PLANET_MAX_IMAGE)
            return og_error_set(err, "size: face image pixels per side, 1 .. %d, got '%s'",
                                EXPORT_PLANET_MAX_IMAGE, value);
    }
    struct timespec t0;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    export_planet_report r;
    if (export_planet(ctx->world, (int)n, argv[2], (int)size, &r, err) != 0) return -1;
    fprintf(ctx->out,
            "exported %s: subdivision %d of the cube, %zu vertices, %zu triangles (watertight); "
            "6 height and 6 normal images of %d x %d pixels (face grid level %d), heights "
            "%.6g .. %.6g m; %d files, %lld bytes; %.2f s\n",
            argv[2], (int)n, r.vertices, r.triangles, r.image_size, r.image_size, r.level, r.min,
            r.max, r.files, r.bytes, seconds_since(&t0));
    return 0;
}

static int require_base(void *pending, grid_rect r, og_error *err) {
    return base_pending_require(pending, r, err);
}

static int base_range(void *pending, grid_rect r, double *lo, double *hi) {
    return base_pending_range(pending, r, lo, hi);
}

int cmd_export(cmd_context *ctx, int argc, char **argv, og_error *err) {
    if (argc >= 3 && export_planet_wanted(argv[1]))
        return export_planet_command(ctx, argc, argv, err);
    export_options o;
    export_options_defaults(&o);
    for (int i = 2; i < argc; i++) {
        char buf[512], *key, *value;
        if (parse_setting(argv[i], buf, sizeof buf, &key, &value, err) != 0 ||
            export_options_set(&o, key, value, err) != 0)
            return -1;
    }
    struct timespec t0;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    if (o.image_layer) {
        char files[8600];
        if (export_layer_file(ctx->world, argv[1], &o, files, sizeof files, err) != 0) return -1;
        for (char *nl = strchr(files, '\n'); nl; nl = strchr(nl, '\n'))
            *nl = nl[1] ? ' ' : 0; // one line: the paths apart by spaces
        fprintf(ctx->out, "exported the %s layer to %s (%.2f s)\n",
                o.image_layer == 1 ? "normal" : "material weight", files, seconds_since(&t0));
        return 0;
    }
    if (export_vdb_wanted(argv[1])) {
        if (o.layers != EXPORT_LAYERS_COMPOSITE)
            return og_error_set(
                err, "%s: layers= applies to heightmap exports (.png .tif .exr .r16)", argv[1]);
        export_vdb_report v;
        if (export_vdb_file(ctx->world, argv[1], &o, &v, err) != 0) return -1;
        fprintf(ctx->out,
                "exported %s: level set 'surface'%s, voxel %.6g m, band %d voxels, %lld active "
                "voxels over %lld columns (%lld volume bricks), solid down to %.6g m; index bounds "
                "%lld,%lld,%lld .. %lld,%lld,%lld; %lld bytes; %.2f s\n",
                argv[1], o.fog ? " and fog volume 'density'" : "", v.voxel, v.band, v.active_voxels,
                v.columns, v.bricks, v.floor, (long long)v.lo[0], (long long)v.lo[1],
                (long long)v.lo[2], (long long)v.hi[0], (long long)v.hi[1], (long long)v.hi[2],
                v.bytes, seconds_since(&t0));
        return 0;
    }
    if (export_mesh_wanted(argv[1])) {
        export_mesh_report m;
        if (export_mesh_file(ctx->world, argv[1], &o, &m, err) != 0) return -1;
        fprintf(ctx->out,
                "exported %s: %zu vertices, %zu triangles (from %zu; %s error %.6g m); "
                "bounds %.6g, %.6g, %.6g .. %.6g, %.6g, %.6g m (+Y up); %.2f s\n",
                argv[1], m.vertices, m.triangles, m.input_triangles,
                m.volume ? "surface" : "height", m.achieved_error, m.lo[0], m.lo[1], m.lo[2],
                m.hi[0], m.hi[1], m.hi[2], seconds_since(&t0));
        return 0;
    }
    // A world imported in parts so far: a heightmap export of the coarse layer imports the
    // parts it reads; anything else needs all of it.
    if (ctx->base_pending) {
        if (o.layer == TILE_LAYER_COARSE && !o.image_layer && !export_vdb_wanted(argv[1]) &&
            !export_mesh_wanted(argv[1])) {
            o.before_read = require_base;
            o.height_range = base_range;
            o.before_read_user = ctx->base_pending;
        } else if (cmd_base_settle(ctx, err) != 0) {
            return -1;
        }
    }
    export_report r;
    char *hints = NULL;
    size_t hints_len = 0;
    FILE *h = open_memstream(&hints, &hints_len);
    if (!h) return og_error_set(err, "export: out of memory");
    int rc = export_heightmap(ctx->world, argv[1], &o, h, &r, err);
    fclose(h);
    if (rc == 0 && r.tiles_total > 0) {
        if (r.changed[0]) fprintf(ctx->out, "%s\n", r.changed);
        fprintf(ctx->out,
                "exported %d of %d tiles of %d x %d samples (%s) for %s: %d x %d samples %.6g m "
                "apart from %.6g, %.6g m; height = stored x %.9g + %.9g m; %lld bytes; %.2f s\n%s",
                r.tiles_written, r.tiles_total, r.tile_width, r.tile_height, r.format, argv[1],
                r.width, r.height, r.spacing, r.origin_x, r.origin_z, r.scale, r.offset, r.bytes,
                seconds_since(&t0), hints);
    } else if (rc == 0) {
        if (r.changed[0]) fprintf(ctx->out, "%s\n", r.changed);
        fprintf(ctx->out,
                "exported %s (%s): %d x %d samples %.6g m apart from %.6g, %.6g m; heights "
                "%.6g .. %.6g m; height = stored x %.9g + %.9g m; %lld bytes with %s.json; "
                "%.2f s\n%s",
                argv[1], r.format, r.width, r.height, r.spacing, r.origin_x, r.origin_z, r.min,
                r.max, r.scale, r.offset, r.bytes, argv[1], seconds_since(&t0), hints);
    }
    free(hints);
    return rc;
}
