#include "editor/cmd/volume_commands.h"

#include "editor/tools/volume_shapes.h"
#include "io/parse.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

// The leading numbers (until the first KEY=VALUE), named X Y Z in turn for messages.
static int numbers(const char *cmd, int argc, char **argv, int dims, double *out, int max,
                   int *count, og_error *err) {
    static const char *const axis3[] = {"X", "Y", "Z"}, *const axis2[] = {"X", "Z"};
    int n = 0;
    for (int i = 1; i < argc && !strchr(argv[i], '='); i++, n++) {
        if (n == max) return og_error_set(err, "%s: at most %d numbers", cmd, max);
        if (parse_number(argv[i], dims == 3 ? axis3[n % 3] : axis2[n % 2], &out[n], err) != 0)
            return -1;
    }
    *count = n;
    return 0;
}

// KEY=VALUE options after the numbers: each names a number in values (same order as
// keys); an unknown key is an error listing the known ones.
static int options(const char *cmd, int argc, char **argv, const char *const *keys, double *values,
                   int key_count, og_error *err) {
    for (int i = 1; i < argc; i++) {
        if (!strchr(argv[i], '=')) continue;
        char buf[256], *key, *value;
        if (parse_setting(argv[i], buf, sizeof buf, &key, &value, err) != 0) return -1;
        int k = 0;
        while (k < key_count && strcmp(keys[k], key) != 0)
            k++;
        if (k == key_count) {
            char known[160] = "";
            for (int j = 0; j < key_count; j++) {
                strcat(known, j ? " " : "");
                strcat(known, keys[j]);
            }
            return og_error_set(err, "%s: unknown option '%s' (%s)", cmd, key, known);
        }
        if (parse_number(value, key, &values[k], err) != 0) return -1;
    }
    return 0;
}

int cmd_arch(cmd_context *ctx, int argc, char **argv, og_error *err) {
    double p[6];
    int n = 0;
    if (numbers(argv[0], argc, argv, 3, p, 6, &n, err) != 0) return -1;
    if (n != 6) return og_error_set(err, "arch: expected X0 Y0 Z0 X1 Y1 Z1 (got %d numbers)", n);
    double span = sqrt((p[3] - p[0]) * (p[3] - p[0]) + (p[5] - p[2]) * (p[5] - p[2]));
    static const char *const keys[] = {"rise", "thickness"};
    double v[2] = {span / 2, 6};
    if (options(argv[0], argc, argv, keys, v, 2, err) != 0) return -1;
    return volume_arch(ctx->world, p, p + 3, v[0], v[1], err);
}

int cmd_tunnel(cmd_context *ctx, int argc, char **argv, og_error *err) {
    double p[3 * 64];
    int n = 0;
    if (numbers(argv[0], argc, argv, 3, p, 3 * 64, &n, err) != 0) return -1;
    if (n < 6 || n % 3)
        return og_error_set(err, "tunnel: expected X Y Z triples, at least 2 (got %d numbers)", n);
    size_t count = (size_t)n / 3;
    double radius[64];
    for (size_t i = 0; i < count; i++)
        radius[i] = 5;
    for (int i = 1; i < argc; i++) {
        if (strncmp(argv[i], "radius=", 7) != 0) {
            if (strchr(argv[i], '='))
                return og_error_set(err, "tunnel: unknown option '%s' (radius=R or R0,R1,...)",
                                    argv[i]);
            continue;
        }
        // One radius for the whole tunnel, or one per point.
        const char *at = argv[i] + 7;
        size_t k = 0;
        double list[64];
        for (;;) {
            const char *end;
            if (k == 64 || parse_scan_f64(at, &list[k], &end) != 0 || (*end && *end != ','))
                return og_error_set(err, "radius: expected R or R0,R1,... in metres, got '%s'",
                                    argv[i] + 7);
            k++;
            if (!*end) break;
            at = end + 1;
        }
        if (k != 1 && k != count)
            return og_error_set(err, "radius: %zu values for %zu points (give 1 or %zu)", k, count,
                                count);
        for (size_t j = 0; j < count; j++)
            radius[j] = list[k == 1 ? 0 : j];
    }
    return volume_tunnel(ctx->world, (const double(*)[3])p, radius, count, err);
}

int cmd_spire(cmd_context *ctx, int argc, char **argv, og_error *err) {
    double p[3];
    int n = 0;
    if (numbers(argv[0], argc, argv, 3, p, 3, &n, err) != 0) return -1;
    if (n != 3) return og_error_set(err, "spire: expected X Y Z (got %d numbers)", n);
    static const char *const keys[] = {"height", "radius", "taper", "cap"};
    double v[4] = {30, 6, 0.3, 0};
    if (options(argv[0], argc, argv, keys, v, 4, err) != 0) return -1;
    return volume_spire(ctx->world, p, v[0], v[1], v[2], v[3], err);
}

int cmd_overhang(cmd_context *ctx, int argc, char **argv, og_error *err) {
    double p[4];
    int n = 0;
    if (numbers(argv[0], argc, argv, 2, p, 4, &n, err) != 0) return -1;
    if (n != 4) return og_error_set(err, "overhang: expected X0 Z0 X1 Z1 (got %d numbers)", n);
    static const char *const keys[] = {"distance", "thickness"};
    double v[2] = {8, 4};
    if (options(argv[0], argc, argv, keys, v, 2, err) != 0) return -1;
    return volume_overhang(ctx->world, p[0], p[1], p[2], p[3], v[0], v[1], err);
}
