#include "io/raster.h"

#include "io/file_kind.h"
#include "io/gdal_raster.h"
#include "io/image_read.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

void raster_free(raster *r) {
    if (!r) return;
    free(r->samples);
    r->samples = NULL;
}

static const char *extension(const char *path) {
    const char *slash = strrchr(path, '/');
    const char *dot = strrchr(slash ? slash : path, '.');
    return dot ? dot + 1 : "";
}

static int ext_in(const char *ext, const char *const *list) {
    for (; *list; list++)
        if (!strcasecmp(ext, *list)) return 1;
    return 0;
}

void raster_metres_per_degree(double latitude, double *per_lat, double *per_lon) {
    // Series for the WGS84 ellipsoid (metres per degree at latitude phi).
    const double phi = latitude * M_PI / 180.0;
    *per_lat = 111132.92 - 559.82 * cos(2 * phi) + 1.175 * cos(4 * phi) - 0.0023 * cos(6 * phi);
    *per_lon = 111412.84 * cos(phi) - 93.5 * cos(3 * phi) + 0.118 * cos(5 * phi);
}

// ---- RAW / R16 --------------------------------------------------------------------

// "250x400, 200x500" : factor pairs of n near a square, for the error message.
static void fitting_sizes(int64_t n, char *out, size_t len) {
    out[0] = 0;
    int found = 0;
    for (int64_t a = (int64_t)sqrt((double)n); a >= 1 && found < 3; a--) {
        if (n % a) continue;
        size_t used = strlen(out);
        snprintf(out + used, len - used, "%s%lldx%lld", found ? ", " : "", (long long)(n / a),
                 (long long)a);
        found++;
    }
}

int raster_read_raw(const char *path, const raster_read_options *o, raster *out, og_error *err) {
    memset(out, 0, sizeof *out);
    raster_read_options none = {0};
    if (!o) o = &none;
    struct stat st;
    if (stat(path, &st) != 0)
        return og_error_set(err, "%s: cannot open: %s", path, strerror(errno));
    if (S_ISDIR(st.st_mode)) return og_error_set(err, "%s: is a folder, not a RAW file", path);
    const int bytes = o->raw_float ? 4 : 2;
    const char *what = o->raw_float ? "float32" : "uint16";
    if (st.st_size % bytes)
        return og_error_set(err, "%s: %lld bytes is not a whole number of %s samples", path,
                            (long long)st.st_size, what);
    const int64_t n = st.st_size / bytes;
    if (n == 0) return og_error_set(err, "%s: the file is empty", path);
    int64_t w = o->width, h = o->height;
    if (w < 0 || h < 0) return og_error_set(err, "%s: width and height must be positive", path);
    if (w && !h) h = n / w;
    if (h && !w) w = n / h;
    const int inferred = !w;
    if (inferred) {
        int64_t side = (int64_t)llround(sqrt((double)n));
        if (side * side == n) w = h = side;
    }
    if (w * h != n || !w) {
        char sizes[128];
        fitting_sizes(n, sizes, sizeof sizes);
        if (inferred)
            return og_error_set(err,
                                "%s: %lld %s samples is not a square; give width= and height= "
                                "(sizes that fit: %s)",
                                path, (long long)n, what, sizes);
        return og_error_set(err,
                            "%s: %lld x %lld is %lld samples but the file holds %lld %s samples "
                            "(sizes that fit: %s)",
                            path, (long long)w, (long long)h, (long long)(w * h), (long long)n,
                            what, sizes);
    }
    if (w > RASTER_MAX_SIZE || h > RASTER_MAX_SIZE || n > RASTER_MAX_SAMPLES)
        return og_error_set(err, "%s: %lld x %lld is over the limit of %d per side", path,
                            (long long)w, (long long)h, RASTER_MAX_SIZE);
    FILE *f = fopen(path, "rb");
    if (!f) return og_error_set(err, "%s: cannot open: %s", path, strerror(errno));
    float *s = malloc(sizeof(float) * (size_t)n);
    unsigned char *buf = malloc((size_t)1 << 20);
    if (!s || !buf) {
        fclose(f), free(s), free(buf);
        return og_error_set(err, "%s: out of memory for %lld samples", path, (long long)n);
    }
    const int big = o->endian == RASTER_BIG;
    int64_t done = 0;
    while (done < n) {
        size_t want = (size_t)((n - done) * bytes < (1 << 20) ? (n - done) * bytes : (1 << 20));
        if (fread(buf, 1, want, f) != want) {
            og_error_set(err, "%s: read failed after %lld samples: %s", path, (long long)done,
                         ferror(f) ? strerror(errno) : "the file got shorter");
            fclose(f), free(s), free(buf);
            return -1;
        }
        for (size_t i = 0; i < want / bytes; i++) {
            const unsigned char *p = buf + i * bytes;
            if (bytes == 2) {
                s[done + i] = big ? (float)(p[0] << 8 | p[1]) : (float)(p[1] << 8 | p[0]);
            } else {
                uint32_t u =
                    big ? (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3]
                        : (uint32_t)p[3] << 24 | (uint32_t)p[2] << 16 | (uint32_t)p[1] << 8 | p[0];
                memcpy(&s[done + i], &u, 4);
            }
        }
        done += (int64_t)(want / bytes);
    }
    fclose(f);
    free(buf);
    out->samples = s;
    out->width = (int)w;
    out->height = (int)h;
    out->kind = o->raw_float ? RASTER_FLOAT : RASTER_UNSIGNED;
    out->bits = bytes * 8;
    snprintf(out->reader, sizeof out->reader, "raw");
    snprintf(out->description, sizeof out->description, "RAW %s %s-endian", what,
             big ? "big" : "little");
    return 0;
}

// ---- voids ------------------------------------------------------------------------

// One pyramid level: the mean of the valid samples of each 2x2 block (NaN if none).
static float *pull_level(const float *s, int w, int h, int *cw, int *ch) {
    *cw = (w + 1) / 2;
    *ch = (h + 1) / 2;
    float *c = malloc(sizeof(float) * (size_t)*cw * (size_t)*ch);
    if (!c) return NULL;
    for (int z = 0; z < *ch; z++)
        for (int x = 0; x < *cw; x++) {
            double sum = 0;
            int count = 0;
            for (int dz = 0; dz < 2; dz++)
                for (int dx = 0; dx < 2; dx++) {
                    int sx = 2 * x + dx, sz = 2 * z + dz;
                    if (sx >= w || sz >= h) continue;
                    float v = s[(size_t)sz * w + sx];
                    if (!isnan(v)) sum += v, count++;
                }
            c[(size_t)z * *cw + x] = count ? (float)(sum / count) : NAN;
        }
    return c;
}

// Fills s's NaN samples from the (complete) coarser level c, bilinearly.
static void push_level(float *s, int w, int h, const float *c, int cw, int ch) {
    for (int z = 0; z < h; z++)
        for (int x = 0; x < w; x++) {
            float *v = &s[(size_t)z * w + x];
            if (!isnan(*v)) continue;
            double fx = (x - 0.5) / 2.0, fz = (z - 0.5) / 2.0;
            int x0 = (int)floor(fx), z0 = (int)floor(fz);
            double tx = fx - x0, tz = fz - z0;
            int xa = x0 < 0 ? 0 : x0, xb = x0 + 1 >= cw ? cw - 1 : x0 + 1;
            int za = z0 < 0 ? 0 : z0, zb = z0 + 1 >= ch ? ch - 1 : z0 + 1;
            double a = c[(size_t)za * cw + xa] * (1 - tx) + c[(size_t)za * cw + xb] * tx;
            double b = c[(size_t)zb * cw + xa] * (1 - tx) + c[(size_t)zb * cw + xb] * tx;
            *v = (float)(a * (1 - tz) + b * tz);
        }
}

static int fill_recursive(float *s, int w, int h) {
    int holes = 0, valid = 0;
    for (size_t i = 0; i < (size_t)w * h; i++) {
        if (isnan(s[i]))
            holes = 1;
        else
            valid = 1;
    }
    if (!holes) return 0;
    if (!valid) return -1;
    int cw, ch;
    float *c = pull_level(s, w, h, &cw, &ch);
    if (!c) return -2;
    int rc = fill_recursive(c, cw, ch);
    if (rc == 0) push_level(s, w, h, c, cw, ch);
    free(c);
    return rc;
}

int64_t raster_fill_voids(float *s, int width, int height) {
    int64_t voids = 0;
    for (size_t i = 0; i < (size_t)width * height; i++) {
        if (isinf(s[i])) s[i] = NAN; // an infinity is no height either
        voids += isnan(s[i]) != 0;
    }
    if (!voids) return 0;
    return fill_recursive(s, width, height) == 0 ? voids : -1;
}

// ---- dispatch ---------------------------------------------------------------------

static int read_gdal(const char *path, raster *out, og_error *err) {
    int kind, bits;
    char desc[160];
    if (gdal_raster_read(path, RASTER_MAX_SIZE, RASTER_MAX_SAMPLES, &out->samples, &out->width,
                         &out->height, &kind, &bits, &out->georef, desc, sizeof desc, err) != 0)
        return -1;
    const double *gt = out->georef.geotransform;
    const int geographic = out->georef.geographic;
    out->kind = (raster_kind)kind;
    out->bits = bits;
    snprintf(out->reader, sizeof out->reader, "gdal");
    if (gt[1] != 0.0 && gt[5] != 0.0 && gt[2] == 0.0 && gt[4] == 0.0) {
        if (geographic) {
            // Degrees: worth their metres at the raster's centre latitude.
            double centre_lat = gt[3] + gt[5] * out->height / 2.0, per_lat, per_lon;
            raster_metres_per_degree(centre_lat, &per_lat, &per_lon);
            out->spacing_x = fabs(gt[1]) * per_lon;
            out->spacing_z = fabs(gt[5]) * per_lat;
            snprintf(out->description, sizeof out->description,
                     "%s, %.6g x %.6g degrees per sample = %.3f x %.3f m at latitude %.4f", desc,
                     fabs(gt[1]), fabs(gt[5]), out->spacing_x, out->spacing_z, centre_lat);
        } else {
            out->spacing_x = fabs(gt[1]);
            out->spacing_z = fabs(gt[5]);
            snprintf(out->description, sizeof out->description, "%s, %.6g x %.6g m per sample",
                     desc, out->spacing_x, out->spacing_z);
        }
    } else {
        snprintf(out->description, sizeof out->description, "%s, not georeferenced", desc);
    }
    return 0;
}

static int read_image(const char *path, const raster_read_options *o, raster *out, og_error *err) {
    int kind, bits;
    if (image_read_channel(path, o->channel, RASTER_MAX_SIZE, &out->samples, &out->width,
                           &out->height, &kind, &bits, out->description, sizeof out->description,
                           err) != 0)
        return -1;
    out->kind = (raster_kind)kind;
    out->bits = bits;
    snprintf(out->reader, sizeof out->reader, "image");
    return 0;
}

int raster_read(const char *path, const raster_read_options *options, raster *out, og_error *err) {
    memset(out, 0, sizeof *out);
    raster_read_options none = {0};
    const raster_read_options *o = options ? options : &none;
    static const char *const raw[] = {"r16", "raw", "r32", NULL};
    static const char *const gdal[] = {"hgt", "tif", "tiff", "asc", "dem", "bil", "bt",
                                       "img", "vrt", "ter",  "flt", "grd", "nc",  NULL};
    const char *ext = extension(path);
    int rc;
    if (file_kind_check_read(path, err) != 0) return -1;
    if (ext_in(ext, raw) || o->raw_float || o->width || o->height) {
        rc = raster_read_raw(path, o, out, err);
    } else if (ext_in(ext, gdal) && !o->channel[0] && gdal_raster_available(NULL, 0)) {
        rc = read_gdal(path, out, err);
    } else {
        rc = read_image(path, o, out, err);
    }
    if (rc != 0) return -1;
    // An image's integers are never NaN (GDAL marks nodata so even in integer rasters):
    // nothing to look for.
    const int no_voids = !strcmp(out->reader, "image") && out->kind != RASTER_FLOAT;
    int64_t filled = no_voids ? 0 : raster_fill_voids(out->samples, out->width, out->height);
    if (filled < 0) {
        raster_free(out);
        return og_error_set(err, "%s: no sample holds a height (all are nodata or NaN)", path);
    }
    out->voids = filled;
    return 0;
}
