#include "editor/interchange/export.h"

#include "editor/interchange/export_fit.h"
#include "editor/interchange/export_layer_read.h"
#include "editor/interchange/export_layers.h"
#include "editor/interchange/sidecar.h"
#include "editor/params/world_georef.h"
#include "editor/world/layer_grid.h"
#include "io/gdal_raster.h"
#include "io/exr_write.h"
#include "io/image_read.h"
#include "io/param_file.h"
#include "io/progress.h"
#include "io/parse.h"
#include "io/path_folder.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/statvfs.h>

static const char *const preset_names[] = {"none",  "unreal",  "unity",
                                           "godot", "houdini", "blender"};

const char *export_preset_name(export_preset p) {
    return preset_names[p];
}

void export_options_defaults(export_options *o) {
    memset(o, 0, sizeof *o);
    o->layer = TILE_LAYER_COARSE;
    o->bits = 0; // the format's default: 32 for .tif, 8 for normal maps
    o->tiles_x = o->tiles_y = 1;
    o->shard_count = 1;
    o->band = 3; // OpenVDB's LEVEL_SET_HALF_WIDTH
    o->depth = -1;
}

// "AxB" or "A/B" as two integers.
static int parse_pair(const char *value, char sep, int *a, int *b) {
    char *end;
    long x = strtol(value, &end, 10);
    if (end == value || *end != sep) return -1;
    const char *second = end + 1;
    long y = strtol(second, &end, 10);
    if (end == second || *end || x < 0 || y < 0 || x > 1 << 20 || y > 1 << 20) return -1;
    *a = (int)x;
    *b = (int)y;
    return 0;
}

int export_options_set(export_options *o, const char *key, const char *value, og_error *err) {
    double v;
    if (!strcmp(key, "region")) {
        double c[4];
        const char *p = value;
        for (int i = 0; i < 4; i++) {
            const char *end;
            if (parse_scan_f64(p, &c[i], &end) != 0 || !isfinite(c[i]) || (i < 3 && *end != ',') ||
                (i == 3 && *end))
                return og_error_set(err, "region: expected X0,Z0,X1,Z1 in metres, got '%s'", value);
            p = end + 1;
        }
        o->x0 = fmin(c[0], c[2]), o->x1 = fmax(c[0], c[2]);
        o->z0 = fmin(c[1], c[3]), o->z1 = fmax(c[1], c[3]);
        o->has_region = 1;
    } else if (!strcmp(key, "preset")) {
        for (int i = 0; i < 6; i++)
            if (!strcmp(value, preset_names[i])) return o->preset = (export_preset)i, 0;
        return og_error_set(
            err, "preset: expected unreal|unity|godot|houdini|blender|none, got '%s'", value);
    } else if (!strcmp(key, "fit")) {
        if (strcmp(value, "crop") && strcmp(value, "resample"))
            return og_error_set(err, "fit: expected crop or resample, got '%s'", value);
        o->fit_crop = value[0] == 'c';
    } else if (!strcmp(key, "layer")) {
        if (!strcmp(value, "coarse"))
            o->layer = TILE_LAYER_COARSE;
        else if (!strcmp(value, "detail"))
            o->layer = TILE_LAYER_DETAIL;
        else if (!strcmp(value, "normals") || !strcmp(value, "materials"))
            o->image_layer = value[0] == 'n' ? 1 : 2;
        else
            return og_error_set(err, "layer: expected coarse|detail|normals|materials, got '%s'",
                                value);
    } else if (!strcmp(key, "layers")) {
        const char *name = value;
        o->layers = EXPORT_LAYERS_DELTA;
        if (!strcmp(value, "composite")) {
            o->layers = EXPORT_LAYERS_COMPOSITE;
            return 0;
        }
        if (!strncmp(value, "upto=", 5)) o->layers = EXPORT_LAYERS_UPTO, name += 5;
        og_error why;
        if (layer_name_check(name, &why) != 0)
            return og_error_set(err, "layers: expected composite, a layer's NAME or upto=NAME; %s",
                                why.msg);
        snprintf(o->layers_name, sizeof o->layers_name, "%s", name);
    } else if (!strcmp(key, "tiles")) {
        if (parse_pair(value, 'x', &o->tiles_x, &o->tiles_y) != 0 || o->tiles_x < 1 ||
            o->tiles_y < 1)
            return og_error_set(err, "tiles: expected COLUMNSxROWS such as 4x4, got '%s'", value);
    } else if (!strcmp(key, "shard")) {
        if (parse_pair(value, '/', &o->shard, &o->shard_count) != 0 || o->shard_count < 1 ||
            o->shard >= o->shard_count)
            return og_error_set(err, "shard: expected I/N with 0 <= I < N, got '%s'", value);
    } else if (!strcmp(key, "pattern")) {
        if (!strstr(value, "{x}") || !strstr(value, "{y}") || strchr(value, '/') ||
            strlen(value) >= sizeof o->pattern)
            return og_error_set(err,
                                "pattern: needs {x} and {y} (and may use {name}), no '/', "
                                "got '%s'",
                                value);
        snprintf(o->pattern, sizeof o->pattern, "%s", value);
    } else if (!strcmp(key, "voxel")) {
        if (parse_number_in(value, key, 1e-3, 1e4, &o->voxel, err) != 0) return -1;
    } else if (!strcmp(key, "band")) {
        double b;
        if (parse_number_in(value, key, 1, 64, &b, err) != 0) return -1;
        if (b != floor(b))
            return og_error_set(err, "band: expected a whole number of voxels, got '%s'", value);
        o->band = (int)b;
    } else if (!strcmp(key, "depth")) {
        if (parse_number_in(value, key, 0, 1e5, &o->depth, err) != 0) return -1;
    } else if (!strcmp(key, "fog")) {
        if (parse_switch(value, key, &o->fog, err) != 0) return -1;
    } else if (!strcmp(key, "simplify")) {
        if (parse_number_in(value, key, 0, 1e6, &o->simplify, err) != 0) return -1;
    } else if (!strcmp(key, "solid") || !strcmp(key, "centred") || !strcmp(key, "centered")) {
        if (parse_switch(value, key, key[0] == 's' ? &o->solid : &o->centred, err) != 0) return -1;
    } else if (!strcmp(key, "bits")) {
        if (strcmp(value, "8") && strcmp(value, "16") && strcmp(value, "32"))
            return og_error_set(err, "bits: expected 8, 16 or 32, got '%s'", value);
        o->bits = atoi(value);
    } else if (!strcmp(key, "min") || !strcmp(key, "max")) {
        if (parse_number(value, key, &v, err) != 0) return -1;
        *(key[1] == 'i' ? &o->min : &o->max) = v;
        o->has_min_max |= key[1] == 'i' ? 1 : 2;
    } else if (!strcmp(key, "scale") || !strcmp(key, "offset")) {
        if (parse_number(value, key, &v, err) != 0) return -1;
        if (key[0] == 's') {
            if (v == 0) return og_error_set(err, "scale: must not be 0");
            o->scale = v;
            o->has_scale |= 1;
        } else {
            o->offset = v;
            o->has_scale |= 2;
        }
    } else {
        return og_error_set(err,
                            "export: unknown option '%s' (region preset fit layer bits min max "
                            "scale offset tiles pattern shard simplify solid centred voxel band "
                            "fog depth)",
                            key);
    }
    return 0;
}

typedef enum file_format { FMT_PNG16, FMT_TIFF16, FMT_TIFF32, FMT_EXR32, FMT_R16 } file_format;
static const char *const format_names[] = {"png16", "tiff16", "tiff32", "exr32", "r16"};

static int format_of(const char *path, int bits, file_format *f, og_error *err) {
    const char *slash = strrchr(path, '/');
    const char *dot = strrchr(slash ? slash : path, '.');
    const char *ext = dot ? dot + 1 : "";
    if (!strcasecmp(ext, "png"))
        *f = FMT_PNG16;
    else if (!strcasecmp(ext, "tif") || !strcasecmp(ext, "tiff")) {
        if (bits == 8)
            return og_error_set(err, "%s: heightmap TIFFs are 16 or 32 bits (bits=16|32)", path);
        *f = bits == 16 ? FMT_TIFF16 : FMT_TIFF32;
    } else if (!strcasecmp(ext, "exr"))
        *f = FMT_EXR32;
    else if (!strcasecmp(ext, "r16") || !strcasecmp(ext, "raw"))
        *f = FMT_R16;
    else
        return og_error_set(
            err, "%s: cannot tell the format: name it .png, .tif, .exr, .r16 or .raw", path);
    return 0;
}

static int is_16bit(file_format f) {
    return f == FMT_PNG16 || f == FMT_TIFF16 || f == FMT_R16;
}

// What the preset requires of the format, and the size of each of C x R tiles sharing
// their edges (*tw x *th, coming in as they fall in the region of W x H samples) that its
// engine imports: the nearest such size, the region resampled to it (*resample set; its
// corners stay on the region's), or with fit=crop the largest that fits, the rest dropped.
// changed says what it did.
static int apply_preset(const char *path, const export_options *o, file_format f, int C, int R,
                        int64_t W, int64_t H, int64_t *tw, int64_t *th, int *resample,
                        char *changed, size_t len, og_error *err) {
    changed[0] = 0;
    *resample = 0;
    int64_t nw = *tw, nh = *th;
    switch (o->preset) {
    case EXPORT_PRESET_NONE:
        if (o->fit_crop)
            return og_error_set(err, "%s: fit= applies to preset=unity|unreal (their sizes)", path);
        return 0;
    case EXPORT_PRESET_UNREAL: {
        if (f != FMT_PNG16 && f != FMT_R16)
            return og_error_set(err,
                                "%s: Unreal's landscape imports 16-bit PNG or R16: name it "
                                ".png or .r16",
                                path);
        // Unreal's recommended landscape sizes (vertices per side).
        static const int sizes[] = {127, 253, 505, 1009, 2017, 4033, 8129};
        if (o->fit_crop) {
            nw = export_fit_largest(sizes, 7, *tw < 8129 ? *tw : 8129);
            nh = export_fit_largest(sizes, 7, *th < 8129 ? *th : 8129);
        } else {
            nw = export_fit_nearest(sizes, 7, W, C);
            nh = export_fit_nearest(sizes, 7, H, R);
        }
        if (!nw || !nh)
            return og_error_set(err,
                                "%s: %lld x %lld samples is under Unreal's smallest landscape "
                                "(127 x 127; fit=resample scales it up)",
                                path, (long long)*tw, (long long)*th);
        break;
    }
    case EXPORT_PRESET_UNITY: {
        if (f != FMT_R16)
            return og_error_set(err, "%s: Unity's terrain imports RAW 16-bit: name it .raw or .r16",
                                path);
        // Square heightmaps of 2^n + 1 (a terrain's width and length are set apart).
        static const int sizes[] = {33, 65, 129, 257, 513, 1025, 2049, 4097};
        if (o->fit_crop) {
            int64_t side = *tw < *th ? *tw : *th;
            nw = nh = export_fit_largest(sizes, 8, side < 4097 ? side : 4097);
        } else {
            int64_t best_miss = INT64_MAX;
            for (int i = 0; i < 8; i++) {
                int64_t miss = llabs((int64_t)C * (sizes[i] - 1) + 1 - W) +
                               llabs((int64_t)R * (sizes[i] - 1) + 1 - H);
                if (miss < best_miss) nw = nh = sizes[i], best_miss = miss;
            }
        }
        if (!nw)
            return og_error_set(err,
                                "%s: %lld x %lld samples is under Unity's smallest terrain "
                                "(33 x 33; fit=resample scales it up)",
                                path, (long long)*tw, (long long)*th);
        break;
    }
    case EXPORT_PRESET_GODOT:
        // Terrain3D's importer reads EXR (and 8/16-bit images), not float TIFF.
        if (f != FMT_EXR32)
            return og_error_set(err, "%s: preset godot takes float heights in metres: name it .exr",
                                path);
        break;
    case EXPORT_PRESET_HOUDINI:
    case EXPORT_PRESET_BLENDER:
        if (f != FMT_EXR32 && f != FMT_TIFF32)
            return og_error_set(err,
                                "%s: preset %s takes float heights in metres: name it .exr "
                                "(or .tif)",
                                path, export_preset_name(o->preset));
        break;
    }
    if (o->preset != EXPORT_PRESET_UNITY && o->preset != EXPORT_PRESET_UNREAL) {
        if (o->fit_crop)
            return og_error_set(err, "%s: fit= applies to preset=unity|unreal (their sizes)", path);
        return 0;
    }
    const int64_t out_w = C * (nw - 1) + 1, out_h = R * (nh - 1) + 1;
    if (!o->fit_crop && (out_w != W || out_h != H)) {
        *resample = 1;
        snprintf(changed, len,
                 "preset %s: resampled the region's %lld x %lld samples to %lld x %lld%s (%lld x "
                 "%lld per tile), the sizes it imports: the same extent, corners on its corners "
                 "(fit=crop keeps the samples and drops the rest)",
                 export_preset_name(o->preset), (long long)W, (long long)H, (long long)out_w,
                 (long long)out_h, C * R > 1 ? " in all" : "", (long long)nw, (long long)nh);
    } else if (nw != *tw || nh != *th) {
        snprintf(changed, len,
                 "preset %s: cropped %lld x %lld samples to %lld x %lld (the sizes it imports), "
                 "keeping the first corner",
                 export_preset_name(o->preset), (long long)*tw, (long long)*th, (long long)nw,
                 (long long)nh);
    }
    *tw = nw;
    *th = nh;
    return 0;
}

static void print_hints(FILE *out, const export_options *o, file_format f, const export_report *r) {
    if (!out) return;
    const double spacing_z = r->spacing_z > 0 ? r->spacing_z : r->spacing;
    const double span_x = (r->width - 1) * r->spacing, span_z = (r->height - 1) * spacing_z;
    if (!is_16bit(f)) {
        fprintf(out, "  heights are metres as stored (float); %g m between samples\n", r->spacing);
        if (o->preset == EXPORT_PRESET_GODOT)
            fprintf(out,
                    "  Godot Terrain3D: import the EXR with scale 1, offset 0, vertex spacing "
                    "%g\n",
                    r->spacing);
        if (o->preset == EXPORT_PRESET_HOUDINI)
            fprintf(out, "  Houdini: HeightField File with grid spacing %g, height scale 1\n",
                    r->spacing);
        if (o->preset == EXPORT_PRESET_BLENDER)
            fprintf(out,
                    "  Blender: displace a %g x %g m grid (%d x %d vertices) by the image, "
                    "strength 1, midlevel 0\n",
                    span_x, span_z, r->width, r->height);
        return;
    }
    // Unreal: height cm = (stored - 32768) / 128 x ScaleZ + LocationZ.
    const double scale_z = 12800.0 * r->scale;
    const double location_z = 100.0 * r->offset + 32768.0 * 100.0 * r->scale;
    if ((o->preset == EXPORT_PRESET_NONE || o->preset == EXPORT_PRESET_UNREAL) &&
        spacing_z == r->spacing)
        fprintf(out,
                "  Unreal landscape: Scale X = Y = %.9g, Scale Z = %.6g, Location Z = %.6g cm\n",
                100.0 * r->spacing, scale_z, location_z);
    else if (o->preset == EXPORT_PRESET_NONE || o->preset == EXPORT_PRESET_UNREAL)
        fprintf(out,
                "  Unreal landscape: Scale X = %.9g, Scale Y = %.9g, Scale Z = %.6g, Location Z = "
                "%.6g cm\n",
                100.0 * r->spacing, 100.0 * spacing_z, scale_z, location_z);
    if (o->preset == EXPORT_PRESET_NONE || o->preset == EXPORT_PRESET_UNITY)
        fprintf(out,
                "  Unity terrain: Import Raw, Depth 16 bit, Byte Order Windows, resolution "
                "%d; Terrain Width %.9g, Length %.9g, Height %.6g m; position Y %.6g m\n",
                r->width, span_x, span_z, 65535.0 * r->scale, r->offset);
}

// Refuses before writing when the folder lacks room for bytes (with a margin).
static int check_space(const char *path, double bytes, og_error *err) {
    char dir[4200];
    path_folder(path, dir, sizeof dir);
    struct statvfs st;
    if (statvfs(dir, &st) != 0)
        return og_error_set(err, "%s: cannot reach its folder: %s", path, strerror(errno));
    double free_bytes = (double)st.f_bavail * (double)st.f_frsize;
    if (free_bytes < bytes * 1.1 + (1 << 20))
        return og_error_set(err, "%s: needs about %.0f MB, but only %.0f MB are free there", path,
                            bytes / 1e6, free_bytes / 1e6);
    return 0;
}

static int write_r16(const char *path, const float *q, int64_t n, og_error *err) {
    unsigned char *bytes = malloc((size_t)n * 2);
    if (!bytes) return og_error_set(err, "%s: out of memory", path);
    for (int64_t i = 0; i < n; i++) {
        uint16_t v = (uint16_t)(q[i] + 0.5f);
        bytes[2 * i] = (unsigned char)(v & 0xff);
        bytes[2 * i + 1] = (unsigned char)(v >> 8);
    }
    int rc = param_file_write_atomic(path, (const char *)bytes, (size_t)n * 2, err);
    free(bytes);
    return rc;
}

static long long file_size(const char *path) {
    FILE *f = fopen(path, "rb");
    if (!f) return 0;
    fseek(f, 0, SEEK_END);
    long long n = ftell(f);
    fclose(f);
    return n;
}

// The 16-bit mapping (height = stored x scale + offset): scale=/offset= or min=/max=
// as given, else lo .. hi spread over 0 .. 65535.
static int mapping_16bit(const export_options *o, double lo, double hi, double *scale,
                         double *offset, og_error *err) {
    if (o->has_scale && o->has_min_max)
        return og_error_set(err, "export: give min=/max= or scale=/offset=, not both");
    if (o->has_scale) {
        *scale = o->has_scale & 1 ? o->scale : 1.0;
        *offset = o->offset;
        return 0;
    }
    if (o->has_min_max == 3) lo = o->min, hi = o->max;
    if (!(hi > lo)) hi = lo + 1.0; // a flat region still needs a step
    *scale = (hi - lo) / 65535.0;
    *offset = lo;
    return 0;
}

// Reads rectangle r of the layer into h a band of tile rows at a time (reading is
// most of an export's time: tiles are loaded or generated), reporting progress in the
// current part and stopping when cancelled. The last step of the part is the write.
static int read_reporting_progress(world *w, const layer_grid *g, const export_options *o,
                                   const char *path, grid_rect r, float *h, og_error *err) {
    if (o->before_read && o->before_read(o->before_read_user, r, err) != 0) return -1;
    og_progress *progress = og_progress_current();
    const int64_t width = r.x1 - r.x0;
    const int64_t first = world_grid_floor_div(r.z0, TILE_SIZE);
    const int64_t bands = world_grid_floor_div(r.z1 - 1, TILE_SIZE) - first + 1;
    for (int64_t b = 0; b < bands; b++) {
        if (og_progress_report(progress, b, bands + 1) != 0)
            return og_error_set(err, "%s: cancelled (nothing written)", path);
        grid_rect band = r;
        band.z0 = b == 0 ? r.z0 : (first + b) * TILE_SIZE;
        band.z1 = b == bands - 1 ? r.z1 : (first + b + 1) * TILE_SIZE;
        if (export_layers_read(w, g, (int)o->layers, o->layers_name, band,
                               h + (band.z0 - r.z0) * width, err) != 0)
            return -1;
    }
    if (og_progress_report(progress, bands, bands + 1) != 0)
        return og_error_set(err, "%s: cancelled (nothing written)", path);
    return 0;
}

// The lowest and highest heights of rectangle r, read a band of tile rows at a time.
static int rect_height_range(world *w, const layer_grid *g, const export_options *o,
                             const char *path, grid_rect r, double *lo, double *hi, og_error *err) {
    if (o->height_range && o->layers == EXPORT_LAYERS_COMPOSITE &&
        o->height_range(o->before_read_user, r, lo, hi))
        return 0;
    if (o->before_read && o->before_read(o->before_read_user, r, err) != 0) return -1;
    const int64_t width = r.x1 - r.x0;
    float *band = malloc(sizeof(float) * (size_t)width * TILE_SIZE);
    if (!band)
        return og_error_set(err, "%s: out of memory for %lld samples", path,
                            (long long)width * TILE_SIZE);
    *lo = INFINITY, *hi = -INFINITY;
    int rc = 0;
    for (int64_t z0 = r.z0; z0 < r.z1 && rc == 0;) {
        if (og_progress_report(og_progress_current(), 0, 1) != 0) {
            rc = og_error_set(err, "%s: cancelled (nothing written)", path);
            break;
        }
        int64_t z1 = (world_grid_floor_div(z0, TILE_SIZE) + 1) * TILE_SIZE;
        if (z1 > r.z1) z1 = r.z1;
        rc = export_layers_read(w, g, (int)o->layers, o->layers_name,
                                (grid_rect){r.x0, z0, r.x1, z1}, band, err);
        for (int64_t i = 0; rc == 0 && i < (z1 - z0) * width; i++) {
            *lo = fmin(*lo, band[i]);
            *hi = fmax(*hi, band[i]);
        }
        z0 = z1;
    }
    free(band);
    return rc;
}

// Output samples r of a preset's resampling (export_fit.h) into h: the region samples
// they read, then resampled.
static int read_resampled(world *w, const layer_grid *g, const export_options *o, const char *path,
                          const export_fit *fit, grid_rect r, float *h, og_error *err) {
    grid_rect s;
    export_fit_source(r.x0, r.x1, fit->out_w, fit->region_w, &s.x0, &s.x1);
    export_fit_source(r.z0, r.z1, fit->out_h, fit->region_h, &s.z0, &s.z1);
    const int64_t sw = s.x1 - s.x0, n = sw * (s.z1 - s.z0);
    float *src = malloc(sizeof(float) * (size_t)n);
    if (!src) return og_error_set(err, "%s: out of memory for %lld samples", path, (long long)n);
    grid_rect in = {fit->region_x0 + s.x0, fit->region_z0 + s.z0, fit->region_x0 + s.x1,
                    fit->region_z0 + s.z1};
    int rc = read_reporting_progress(w, g, o, path, in, src, err);
    if (rc == 0)
        export_fit_resample(fit, src, sw, s.x0, s.z0, r.x0, r.z0, r.x1 - r.x0, r.z1 - r.z0, h);
    free(src);
    return rc;
}

// Reads rectangle r of the layer (with fit: output samples r of the region resampled)
// and writes it to path with its sidecar. The 16-bit mapping is rep's when fixed_mapping
// (tiles share one), else chosen from o and the rectangle's range.
static int write_rect(world *w, const layer_grid *g, const char *path, const export_options *o,
                      file_format f, grid_rect r, const export_fit *fit, int fixed_mapping,
                      export_report *rep, og_error *err) {
    const int64_t w64 = r.x1 - r.x0, h64 = r.z1 - r.z0, n = w64 * h64;
    const double bytes_estimate = (double)n * (is_16bit(f) ? 2.0 : 4.0);
    if (check_space(path, bytes_estimate, err) != 0) return -1;
    float *h = malloc(sizeof(float) * (size_t)n);
    if (!h) return og_error_set(err, "%s: out of memory for %lld samples", path, (long long)n);
    int rc = -1;
    if ((fit ? read_resampled(w, g, o, path, fit, r, h, err)
             : read_reporting_progress(w, g, o, path, r, h, err)) != 0)
        goto done;
    rep->min = INFINITY, rep->max = -INFINITY;
    for (int64_t i = 0; i < n; i++) {
        rep->min = fmin(rep->min, h[i]);
        rep->max = fmax(rep->max, h[i]);
    }
    rep->width = (int)w64;
    rep->height = (int)h64;
    rep->spacing = fit ? export_fit_spacing_x(fit, g->spacing) : g->spacing;
    rep->spacing_z = fit ? export_fit_spacing_z(fit, g->spacing) : g->spacing;
    rep->origin_x =
        fit ? ((double)fit->region_x0 + export_fit_position(r.x0, fit->out_w, fit->region_w)) *
                  g->spacing
            : (double)r.x0 * g->spacing;
    rep->origin_z =
        fit ? ((double)fit->region_z0 + export_fit_position(r.z0, fit->out_h, fit->region_h)) *
                  g->spacing
            : (double)r.z0 * g->spacing;
    snprintf(rep->format, sizeof rep->format, "%s", format_names[f]);
    if (!fixed_mapping) rep->scale = 1.0, rep->offset = 0.0;
    if (is_16bit(f) && !fixed_mapping &&
        mapping_16bit(o, rep->min, rep->max, &rep->scale, &rep->offset, err) != 0)
        goto done;
    if (is_16bit(f)) {
        for (int64_t i = 0; i < n; i++) {
            double q = round((h[i] - rep->offset) / rep->scale);
            if (q < 0 || q > 65535) {
                og_error_set(err,
                             "%s: height %g m at sample (%lld, %lld) is outside the 16-bit range "
                             "%g .. %g m of this mapping",
                             path, (double)h[i], (long long)(i % w64), (long long)(i / w64),
                             rep->offset, rep->offset + 65535.0 * rep->scale);
                goto done;
            }
            h[i] = (float)q;
        }
    }
    // Where the samples lie: the world's georeference (a world made from a DEM), else
    // local metres north-up (rows toward +Z, i.e. south).
    const world_params *wp = world_get_params(w);
    const int ratio = o->layer == TILE_LAYER_DETAIL ? wp->detail_ratio : 1;
    double gt[6];
    if (fit)
        export_fit_georef(wp, ratio, fit, r.x0, r.z0, gt);
    else
        world_georef_region(wp, ratio, r.x0, r.z0, gt);
    switch (f) {
    case FMT_PNG16:
        rc = image_write_samples(path, h, rep->width, rep->height, IMAGE_WRITE_UINT16, NULL, err);
        break;
    case FMT_EXR32:
        rc = exr_write_float(path, h, rep->width, rep->height, "Y", err);
        break;
    case FMT_TIFF16:
    case FMT_TIFF32:
        rc = gdal_raster_write_geotiff(path, h, rep->width, rep->height, f == FMT_TIFF16,
                                       rep->scale, rep->offset, gt, wp->geo_crs, err);
        break;
    case FMT_R16:
        rc = write_r16(path, h, n, err);
        break;
    }
    if (rc != 0) goto done;
    sidecar sc = {.spacing = rep->spacing,
                  .spacing_z = rep->spacing_z,
                  .origin_x = rep->origin_x,
                  .origin_z = rep->origin_z,
                  .width = rep->width,
                  .height = rep->height,
                  .scale = rep->scale,
                  .offset = rep->offset,
                  .min = rep->min,
                  .max = rep->max};
    snprintf(sc.format, sizeof sc.format, "%s", rep->format);
    snprintf(sc.layer, sizeof sc.layer, "%s", o->layer == TILE_LAYER_DETAIL ? "detail" : "coarse");
    char extra[8192] = "";
    if (o->preset != EXPORT_PRESET_NONE)
        snprintf(extra, sizeof extra, "  \"preset\": \"%s\"", export_preset_name(o->preset));
    if (o->layers != EXPORT_LAYERS_COMPOSITE) // what the heights are: a layer's change or a part
        snprintf(extra + strlen(extra), sizeof extra - strlen(extra),
                 "%s  \"layers\": \"%s\",\n  \"edit_layer\": \"%s\"", extra[0] ? ",\n" : "",
                 o->layers == EXPORT_LAYERS_DELTA ? "change" : "upto", o->layers_name);
    if (world_georef_present(wp))
        sidecar_georef(extra + strlen(extra), sizeof extra - strlen(extra), extra[0] != 0,
                       wp->geo_crs, gt);
    rc = sidecar_write(path, &sc, extra, err);
    if (rc != 0) goto done;
    char json[4200];
    snprintf(json, sizeof json, "%s.json", path);
    rep->bytes = file_size(path) + file_size(json);
done:
    free(h);
    return rc;
}

// The file name of tile (x, y): the pattern with {name} {x} {y} filled in, in
// path's folder with path's extension.
static int tile_path(const char *path, const char *pattern, int x, int y, char *out, size_t len) {
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    const char *dot = strrchr(base, '.');
    char name[512];
    snprintf(name, sizeof name, "%.*s", (int)(dot ? dot - base : (long)strlen(base)), base);
    char file[1024] = "";
    size_t n = 0;
    for (const char *p = pattern; *p && n + 16 < sizeof file;) {
        if (!strncmp(p, "{name}", 6)) {
            n += (size_t)snprintf(file + n, sizeof file - n, "%s", name);
            p += 6;
        } else if (!strncmp(p, "{x}", 3) || !strncmp(p, "{y}", 3)) {
            n += (size_t)snprintf(file + n, sizeof file - n, "%d", p[1] == 'x' ? x : y);
            p += 3;
        } else {
            file[n++] = *p++;
            file[n] = 0;
        }
    }
    int written = snprintf(out, len, "%.*s%s%s", (int)(slash ? slash - path + 1 : 0), path, file,
                           dot ? dot : "");
    return written < (int)len ? 0 : -1;
}

// Tiles of one size sharing their edge samples (what Unreal's and Unity's tiled
// imports expect), one 16-bit mapping for all, and the set's sidecar.
static int export_tiles(world *w, const layer_grid *g, const char *path, const export_options *o,
                        file_format f, grid_rect r, FILE *hints, export_report *report,
                        og_error *err) {
    const int C = o->tiles_x, R = o->tiles_y;
    const int64_t W = r.x1 - r.x0, H = r.z1 - r.z0;
    int64_t tw = (W - 1) / C + 1, th = (H - 1) / R + 1;
    // A preset sizes each tile as its engine imports one (the set follows).
    char preset_change[512];
    int resample;
    if (apply_preset(path, o, f, C, R, W, H, &tw, &th, &resample, preset_change,
                     sizeof preset_change, err) != 0)
        return -1;
    if (tw < 2 || th < 2)
        return og_error_set(err,
                            "%s: %lld x %lld samples cannot make %d x %d tiles of 2 samples "
                            "or more",
                            path, (long long)W, (long long)H, C, R);
    if (tw > EXPORT_MAX_SIDE || th > EXPORT_MAX_SIDE || tw * th > EXPORT_MAX_SAMPLES)
        return og_error_set(err,
                            "%s: tiles of %lld x %lld samples are over the limit of %d per "
                            "side: use more tiles",
                            path, (long long)tw, (long long)th, EXPORT_MAX_SIDE);
    export_report rep;
    memset(&rep, 0, sizeof rep);
    // The output: the tiles' samples, sharing edges; resampled, the whole region's.
    const export_fit fit = {r.x0, r.z0, W, H, C * (tw - 1) + 1, R * (th - 1) + 1};
    const int64_t used_w = resample ? W : fit.out_w, used_h = resample ? H : fit.out_h;
    if (resample)
        snprintf(rep.changed, sizeof rep.changed, "%s", preset_change);
    else if (used_w != W || used_h != H)
        snprintf(rep.changed, sizeof rep.changed,
                 "%.200s%stiles: the region is %lld x %lld samples; %d x %d tiles of %lld x %lld "
                 "sharing their edges cover %lld x %lld of it (from the first corner)",
                 preset_change, preset_change[0] ? " per tile; " : "", (long long)W, (long long)H,
                 C, R, (long long)tw, (long long)th, (long long)used_w, (long long)used_h);
    // One mapping for every tile and every shard: what was given, else the heights of
    // all the tiles cover (every shard reads them, so every shard agrees).
    rep.scale = 1.0, rep.offset = 0.0;
    char mapping[256] = "";
    if (is_16bit(f)) {
        double lo = 0, hi = 0;
        const int given = o->has_scale || o->has_min_max == 3;
        grid_rect used = {r.x0, r.z0, r.x0 + used_w, r.z0 + used_h};
        if (!given && rect_height_range(w, g, o, path, used, &lo, &hi, err) != 0) return -1;
        if (mapping_16bit(o, lo, hi, &rep.scale, &rep.offset, err) != 0) return -1;
        if (given)
            snprintf(mapping, sizeof mapping,
                     "one for every tile, as given: stored 0 .. 65535 = %.9g .. %.9g m", rep.offset,
                     rep.offset + 65535.0 * rep.scale);
        else
            snprintf(mapping, sizeof mapping,
                     "one for every tile: the region's heights %.9g .. %.9g m over stored 0 .. "
                     "65535",
                     lo, hi);
    }
    const char *pattern = o->pattern[0]                      ? o->pattern
                          : o->preset == EXPORT_PRESET_UNITY ? "{name}_{x}_{y}"
                                                             : "{name}_x{x}_y{y}";
    char *files = NULL;
    size_t files_len = 0;
    FILE *list = open_memstream(&files, &files_len);
    if (!list) return og_error_set(err, "%s: out of memory", path);
    if (mapping[0]) fprintf(list, "  \"height_mapping\": \"%s\",\n", mapping);
    fprintf(list,
            "  \"tiles_x\": %d,\n  \"tiles_y\": %d,\n  \"tile_width\": %lld,\n"
            "  \"tile_height\": %lld,\n  \"overlap\": 1,\n  \"pattern\": \"%s\",\n"
            "  \"files\": [",
            C, R, (long long)tw, (long long)th, pattern);
    int rc = 0;
    for (int y = 0; y < R && rc == 0; y++)
        for (int x = 0; x < C && rc == 0; x++) {
            char tp[4200];
            if (tile_path(path, pattern, x, y, tp, sizeof tp) != 0) {
                rc = og_error_set(err, "%s: tile name too long", path);
                break;
            }
            const char *slash = strrchr(tp, '/');
            fprintf(list, "%s\"%s\"", x || y ? ", " : "", slash ? slash + 1 : tp);
            // Shard I takes the I-th of N contiguous runs of tiles (row-major): neighbours
            // share the cache tiles along their seam, so few are generated twice.
            const int64_t k = (int64_t)y * C + x;
            if (k * o->shard_count / ((int64_t)C * R) != o->shard) continue;
            if (og_progress_report(og_progress_current(), y * C + x, (int64_t)C * R) != 0) {
                // Tiles already written stay (each whole, with its sidecar); the set's
                // sidecar is not written, so the set reads as unfinished.
                rc = og_error_set(err, "%s: cancelled after %d of %d tiles", path,
                                  rep.tiles_written, C * R);
                break;
            }
            // Resampled: the tile's output samples; else the region's samples it holds.
            grid_rect t = {x * (tw - 1), y * (th - 1), 0, 0};
            if (!resample) t.x0 += r.x0, t.z0 += r.z0;
            t.x1 = t.x0 + tw;
            t.z1 = t.z0 + th;
            export_report one = rep;
            og_progress_part outer = og_progress_enter(og_progress_current(), k, (int64_t)C * R);
            rc = write_rect(w, g, tp, o, f, t, resample ? &fit : NULL, 1, &one, err);
            og_progress_leave(og_progress_current(), outer);
            if (rc == 0) {
                rep.bytes += one.bytes;
                rep.tiles_written++;
                rep.min = rep.tiles_written == 1 ? one.min : fmin(rep.min, one.min);
                rep.max = rep.tiles_written == 1 ? one.max : fmax(rep.max, one.max);
            }
        }
    fprintf(list, "]");
    fclose(list);
    rep.width = (int)fit.out_w;
    rep.height = (int)fit.out_h;
    rep.tile_width = (int)tw;
    rep.tile_height = (int)th;
    rep.tiles_total = C * R;
    rep.spacing = resample ? export_fit_spacing_x(&fit, g->spacing) : g->spacing;
    rep.spacing_z = resample ? export_fit_spacing_z(&fit, g->spacing) : g->spacing;
    rep.origin_x = (double)r.x0 * g->spacing;
    rep.origin_z = (double)r.z0 * g->spacing;
    snprintf(rep.format, sizeof rep.format, "%s", format_names[f]);
    if (rc == 0 && o->shard == 0) {
        // The set's sidecar depends on nothing another shard does: every shard agrees.
        sidecar sc = {.spacing = rep.spacing,
                      .spacing_z = rep.spacing_z,
                      .origin_x = rep.origin_x,
                      .origin_z = rep.origin_z,
                      .width = rep.width,
                      .height = rep.height,
                      .scale = rep.scale,
                      .offset = rep.offset};
        snprintf(sc.format, sizeof sc.format, "%s", rep.format);
        snprintf(sc.layer, sizeof sc.layer, "%s",
                 o->layer == TILE_LAYER_DETAIL ? "detail" : "coarse");
        sc.min = rep.offset;
        sc.max = is_16bit(f) ? rep.offset + 65535.0 * rep.scale : 0.0;
        const world_params *wp = world_get_params(w);
        if (world_georef_present(wp)) {
            // The set's place: its first tile's corner, the tiles' sample size.
            double gt[6];
            const int ratio = o->layer == TILE_LAYER_DETAIL ? wp->detail_ratio : 1;
            if (resample)
                export_fit_georef(wp, ratio, &fit, 0, 0, gt);
            else
                world_georef_region(wp, ratio, r.x0, r.z0, gt);
            char geo[8192];
            sidecar_georef(geo, sizeof geo, 1, wp->geo_crs, gt);
            char *joined = malloc(strlen(files) + strlen(geo) + 1);
            if (!joined) {
                free(files);
                return og_error_set(err, "%s: out of memory", path);
            }
            strcpy(joined, files);
            strcat(joined, geo);
            free(files);
            files = joined;
        }
        rc = sidecar_write(path, &sc, files, err);
    }
    free(files);
    if (rc != 0) return -1;
    // The engine takes one tile at a time: its settings, then where each tile goes.
    export_report tile = rep;
    tile.width = (int)tw, tile.height = (int)th;
    if (hints && mapping[0]) fprintf(hints, "  height mapping: %s\n", mapping);
    if (hints) fprintf(hints, "  each tile (%lld x %lld samples):\n", (long long)tw, (long long)th);
    print_hints(hints, o, f, &tile);
    if (hints)
        fprintf(hints,
                "  the set: %d x %d tiles covering %.9g x %.9g m; tile (x, y) starts at X = %.9g "
                "+ x * %.9g m, Z = %.9g + y * %.9g m%s\n",
                C, R, (double)(fit.out_w - 1) * rep.spacing,
                (double)(fit.out_h - 1) * rep.spacing_z, rep.origin_x,
                (double)(tw - 1) * rep.spacing, rep.origin_z, (double)(th - 1) * rep.spacing_z,
                o->preset == EXPORT_PRESET_UNREAL
                    ? " (Unreal: Import from File with the _x{x}_y{y} tiles, section size to fit)"
                : o->preset == EXPORT_PRESET_UNITY ? " (Unity: one terrain per tile, neighbours "
                                                     "connected)"
                                                   : "");
    if (report) *report = rep;
    return 0;
}

// The layer's samples the export covers: region= (corners in metres, clipped to a
// bounded world) or the whole bounded world.
static int resolve_region(world *w, const char *path, const export_options *o, layer_grid *gp,
                          grid_rect *rp, og_error *err) {
    const world_params *p = world_get_params(w);
    if (layer_grid_init(gp, p, o->layer, 0, err) != 0) return -1;
    grid_rect r;
    if (o->has_region) {
        r = (grid_rect){(int64_t)ceil(o->x0 / gp->spacing - 1e-9),
                        (int64_t)ceil(o->z0 / gp->spacing - 1e-9),
                        (int64_t)floor(o->x1 / gp->spacing + 1e-9) + 1,
                        (int64_t)floor(o->z1 / gp->spacing + 1e-9) + 1};
        if (fabs(o->x0) > 1e15 || fabs(o->x1) > 1e15 || fabs(o->z0) > 1e15 || fabs(o->z1) > 1e15)
            return og_error_set(err, "%s: region is beyond any world", path);
        if (gp->extent) r = layer_grid_clip(gp, r);
    } else {
        if (!gp->extent)
            return og_error_set(err, "%s: the world is unbounded: give region=X0,Z0,X1,Z1 (metres)",
                                path);
        r = (grid_rect){0, 0, gp->extent, gp->extent_z};
    }
    *rp = r;
    return 0;
}

_Static_assert((int)EXPORT_LAYERS_DELTA == (int)EXPORT_READ_CHANGE &&
                   (int)EXPORT_LAYERS_UPTO == (int)EXPORT_READ_UPTO,
               "export_layer_read.h reads export_layers values");

// layers= picks what a heightmap holds; the other exports take the composite.
static int composite_only(const char *path, const export_options *o, og_error *err) {
    if (o->layers == EXPORT_LAYERS_COMPOSITE) return 0;
    return og_error_set(err, "%s: layers= applies to heightmap exports (.png .tif .exr .r16)",
                        path);
}

int export_layer_file(world *w, const char *path, const export_options *o, char *files,
                      size_t files_len, og_error *err) {
    if (composite_only(path, o, err) != 0) return -1;
    if (world_get_params(w)->kind == WORLD_PLANET)
        return og_error_set(err, "%s: layer images are exported from flat worlds", path);
    layer_grid g;
    grid_rect r;
    if (resolve_region(w, path, o, &g, &r, err) != 0) return -1;
    const int64_t W = r.x1 - r.x0, D = r.z1 - r.z0;
    if (W < 1 || D < 1 || W > 16384 || D > 16384)
        return og_error_set(err, "%s: %lld x %lld samples: layer images are 1 to 16384 per side",
                            path, (long long)W, (long long)D);
    if (o->image_layer == 1) {
        if (o->bits == 32)
            return og_error_set(err, "%s: normal maps are 8 or 16 bits (bits=8|16)", path);
        return export_normal_map(w, path, r, o->bits == 16 ? 16 : 8, files, files_len, err);
    }
    if (o->bits != 0 && o->bits != 8)
        return og_error_set(err, "%s: material weights are stored as 8 bits; bits= does not apply",
                            path);
    return export_material_weights(w, path, r, files, files_len, err);
}

int export_mesh_file(world *w, const char *path, const export_options *o, export_mesh_report *rep,
                     og_error *err) {
    if (world_get_params(w)->kind == WORLD_PLANET)
        return og_error_set(err, "%s: meshes are exported from flat worlds", path);
    if (o->layer != TILE_LAYER_COARSE)
        return og_error_set(err, "%s: meshes are made of the coarse layer", path);
    if (composite_only(path, o, err) != 0) return -1;
    layer_grid g;
    export_mesh_options m = {.simplify = o->simplify, .solid = o->solid, .centred = o->centred};
    if (resolve_region(w, path, o, &g, &m.rect, err) != 0) return -1;
    return export_mesh(w, path, &m, rep, err);
}

int export_heightmap(world *w, const char *path, const export_options *o, FILE *hints,
                     export_report *report, og_error *err) {
    const world_params *p = world_get_params(w);
    if (p->kind == WORLD_PLANET)
        return og_error_set(err, "export: planets are exported by their own issue's tools, not as "
                                 "one heightmap");
    file_format f = FMT_PNG16;
    if (format_of(path, o->bits, &f, err) != 0) return -1;
    layer_grid g;
    grid_rect r;
    if (export_layers_check(w, path, (int)o->layers, o->layers_name, o->layer, err) != 0 ||
        resolve_region(w, path, o, &g, &r, err) != 0)
        return -1;
    int64_t w64 = r.x1 - r.x0, h64 = r.z1 - r.z0;
    if (o->tiles_x * o->tiles_y > 1) return export_tiles(w, &g, path, o, f, r, hints, report, err);
    if (o->shard_count > 1)
        return og_error_set(err, "%s: shard= splits a tiled export: give tiles=CxR too", path);
    if (w64 < 2 || h64 < 2)
        return og_error_set(err,
                            "%s: the region holds %lld x %lld samples; a heightmap needs at "
                            "least 2 x 2 (%g m between samples)",
                            path, (long long)(w64 > 0 ? w64 : 0), (long long)(h64 > 0 ? h64 : 0),
                            g.spacing);
    if (w64 > EXPORT_MAX_SIDE || h64 > EXPORT_MAX_SIDE || w64 * h64 > EXPORT_MAX_SAMPLES)
        return og_error_set(err,
                            "%s: the region is %lld x %lld samples, over the limit of %d per "
                            "side and %lld in all (export it as tiles)",
                            path, (long long)w64, (long long)h64, EXPORT_MAX_SIDE,
                            (long long)EXPORT_MAX_SAMPLES);
    export_report rep;
    memset(&rep, 0, sizeof rep);
    int64_t ow = w64, oh = h64;
    int resample;
    if (apply_preset(path, o, f, 1, 1, w64, h64, &ow, &oh, &resample, rep.changed,
                     sizeof rep.changed, err) != 0)
        return -1;
    const export_fit fit = {r.x0, r.z0, w64, h64, ow, oh};
    if (resample) r = (grid_rect){0, 0, ow, oh}; // the output's samples
    r.x1 = r.x0 + ow;
    r.z1 = r.z0 + oh;
    if (write_rect(w, &g, path, o, f, r, resample ? &fit : NULL, 0, &rep, err) != 0) return -1;
    print_hints(hints, o, f, &rep);
    if (report) *report = rep;
    return 0;
}
