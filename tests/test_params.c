// Parameter files: the tolerant reader, the atomic writer, and world parameters
// (defaults, keys, diagnostics, exact round trip, tile store path resolution).
#include "editor/params/world_params.h"
#include "io/param_file.h"
#include "support/test_support.h"

#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <unistd.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

// Collects the messages world_params_load reports.
typedef struct messages {
    char text[256][512];
    size_t count;
} messages;

static void collect(void *user, const char *message) {
    messages *m = user;
    if (m->count < 256) snprintf(m->text[m->count++], sizeof m->text[0], "%s", message);
}

static int has_message(const messages *m, const char *text) {
    for (size_t i = 0; i < m->count; i++)
        if (!strcmp(m->text[i], text)) return 1;
    return 0;
}

static int has_message_prefix(const messages *m, const char *prefix) {
    for (size_t i = 0; i < m->count; i++)
        if (!strncmp(m->text[i], prefix, strlen(prefix))) return 1;
    return 0;
}

static void print_messages(const messages *m) {
    for (size_t i = 0; i < m->count; i++)
        print_message("  report: %s\n", m->text[i]);
}

// Writes text to dir/name and loads it; returns the load status.
static int load_text(const char *dir, const char *name, const char *text, size_t len,
                     world_params *p, int *errors, messages *m, char *path, size_t path_len) {
    snprintf(path, path_len, "%s/%s", dir, name);
    test_write_file(path, text, len);
    memset(m, 0, sizeof *m);
    og_error err = {{0}};
    int rc = world_params_load(path, p, errors, collect, m, &err);
    print_messages(m);
    return rc;
}

// Two parameter sets are equal when every key reads the same (the canonical text of a
// double is exact, so this compares bits).
static void assert_params_equal(const world_params *a, const world_params *b) {
    for (size_t i = 0; i < world_params_key_count(); i++) {
        char x[1100], y[1100];
        const char *key = world_params_key(i);
        assert_int_equal(world_params_get(a, key, x, sizeof x), 0);
        assert_int_equal(world_params_get(b, key, y, sizeof y), 0);
        if (strcmp(x, y)) print_message("key %s: '%s' != '%s'\n", key, x, y);
        assert_string_equal(x, y);
    }
}

static void test_seed004_planet_loads_unchanged(void **state) {
    (void)state;
    world_params p;
    int errors = -1;
    messages m = {0};
    og_error err = {{0}};
    const char *path = OROGEN_TEST_DATA "/params/seed004.planet";
    assert_int_equal(world_params_load(path, &p, &errors, collect, &m, &err), 0);
    print_messages(&m);
    assert_int_equal(errors, 0);
    assert_int_equal(m.count, 0);
    assert_int_equal(p.kind, WORLD_PLANET);
    assert_int_equal(p.generator, GEN_FBM_ADVANCED);
    assert_true(p.radius == 10.0);
    assert_true(p.max_height == 0.5);
    assert_true(p.ocean_level == 10.1);
    // Seed 004's meaning: a radius, the sea 0.1 above the datum.
    assert_true(fabs(world_params_ocean_height(&p) - 0.1) < 1e-12);
    assert_true(p.omega == 0.1);
    assert_true(p.seed == 12345);
    assert_true(p.w_factor == 0.5);
    assert_true(p.exponent == 2.0);
    // Keys the file does not set keep the planet defaults.
    world_params d;
    world_params_default(&d, WORLD_PLANET);
    assert_true(p.octaves == d.octaves);
    assert_true(p.spacing == d.spacing);
    assert_string_equal(p.tiles, "");
    assert_int_equal(world_params_validate(&p, &err), 0);
}

static void test_defaults_are_valid(void **state) {
    (void)state;
    og_error err = {{0}};
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    assert_int_equal(p.kind, WORLD_FLAT);
    assert_int_equal(world_params_validate(&p, &err), 0);
    assert_true(p.ocean_level < 0 && p.ocean_level > -p.max_height);
    assert_int_equal(p.size, 0);
    assert_int_equal(p.detail_ratio, 4);
    assert_true(p.roughness == 0.4 && p.smoothing == 0.5 && p.ridge_offset == 1.0);
    world_params_default(&p, WORLD_PLANET);
    assert_int_equal(p.kind, WORLD_PLANET);
    assert_int_equal(p.generator, GEN_FBM_ADVANCED);
    assert_true(p.radius == 6371000 && p.max_height == 8848 && p.ocean_level == p.radius);
    assert_true(world_params_ocean_height(&p) == 0);
    assert_int_equal(world_params_validate(&p, &err), 0);
}

static void test_key_table(void **state) {
    (void)state;
    static const char *const expected[] = {
        "kind",         "generator",    "seed",        "octaves",       "w_factor",
        "exponent",     "max_height",   "ocean_level", "radius",        "omega",
        "atmosphere",   "spacing",      "size",        "size_z",        "detail_ratio",
        "volume_ratio", "feature_size", "base_height", "roughness",     "smoothing",
        "ridge_offset", "fault_count",  "geo_crs",     "geo_transform", "tiles",
        "tiles_id",     "tiles_saved"};
    size_t n = sizeof expected / sizeof expected[0];
    assert_int_equal(world_params_key_count(), n);
    for (size_t i = 0; i < n; i++) {
        assert_string_equal(world_params_key(i), expected[i]);
        const char *help = world_params_key_help(expected[i]);
        assert_non_null(help);
        assert_true(strlen(help) > 10 && !strchr(help, '\n'));
    }
    assert_null(world_params_key(n));
    assert_null(world_params_key_help("nope"));
    for (int g = 0; g < GEN_COUNT; g++) {
        assert_int_equal(gen_kind_parse(gen_kind_name((gen_kind)g)), g);
        char idx[8];
        snprintf(idx, sizeof idx, "%d", g);
        assert_int_equal(gen_kind_parse(idx), g);
    }
    assert_int_equal(gen_kind_parse("8"), -1);
    assert_int_equal(gen_kind_parse("-1"), -1);
    assert_int_equal(gen_kind_parse("perlin"), -1);
    assert_int_equal(gen_kind_parse(""), -1);
    assert_null(gen_kind_name(GEN_COUNT));
}

// One good value per key and the canonical text it reads back as.
typedef struct good_case {
    const char *key, *value, *canonical;
} good_case;

static void test_set_get_every_key(void **state) {
    (void)state;
    static const good_case good[] = {
        {"kind", "planet", "planet"},
        {"kind", "flat", "flat"},
        {"generator", "1", "fbm_advanced"},
        {"generator", "diamond_square", "diamond_square"},
        {"generator", "5", "flat"},
        {"seed", "-9223372036854775808", "-9223372036854775808"},
        {"seed", "9223372036854775807", "9223372036854775807"},
        {"seed", "42", "42"},
        {"octaves", "12.5", "12.5"},
        {"octaves", "30", "30"},
        {"w_factor", "0.65", "0.65"},
        {"exponent", "2.1", "2.1"},
        {"exponent", "8", "8"},
        {"max_height", "1e6", "1000000"},
        {"ocean_level", "-1e-300", "-1e-300"},
        {"radius", "6371000", "6371000"},
        {"omega", "-7.2921e-5", "-7.2921e-05"},
        {"atmosphere", "0", "0"},
        {"atmosphere", "0.6", "0.6"},
        {"spacing", "0.25", "0.25"},
        {"size", "0", "0"},
        {"size", "4097", "4097"},
        {"size", "549755813888", "549755813888"},
        {"detail_ratio", "1", "1"},
        {"detail_ratio", "64", "64"},
        {"volume_ratio", "1", "1"},
        {"volume_ratio", "8", "8"},
        {"feature_size", "0", "0"},
        {"feature_size", "2500.5", "2500.5"},
        {"base_height", "-12.75", "-12.75"},
        {"roughness", "2", "2"},
        {"smoothing", "0", "0"},
        {"ridge_offset", "0.9", "0.9"},
        {"fault_count", "10000", "10000"},
        {"tiles", "sub/my world.tiles", "sub/my world.tiles"},
        {"tiles", "", ""},
        {"tiles_id", "0123456789abcdef0123456789abcdef", "0123456789abcdef0123456789abcdef"},
        {"tiles_id", "", ""},
        {"tiles_saved", "12", "12"},
        {"tiles_saved", "-1", "-1"},
        {"size_z", "800", "800"},
        {"size_z", "0", "0"},
        {"geo_crs", "EPSG:32619", "EPSG:32619"},
        {"geo_crs", "GEOGCS[\"WGS 84\",AUTHORITY[\"EPSG\",\"4326\"]]",
         "GEOGCS[\"WGS 84\",AUTHORITY[\"EPSG\",\"4326\"]]"},
        {"geo_crs", "", ""},
        {"geo_transform",
         "-72.000416666666666,0.00083333333333333339,0,45.000416666666666, 0, "
         "-0.00083333333333333339",
         "-72.00041666666667, 0.0008333333333333334, 0, 45.000416666666666, 0, "
         "-0.0008333333333333334"},
        {"geo_transform", "", ""},
    };
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    for (size_t i = 0; i < sizeof good / sizeof good[0]; i++) {
        og_error err = {{0}};
        char buf[1100];
        if (world_params_set(&p, good[i].key, good[i].value, &err) != 0)
            print_message("%s = %s: %s\n", good[i].key, good[i].value, err.msg);
        assert_int_equal(world_params_set(&p, good[i].key, good[i].value, &err), 0);
        assert_int_equal(world_params_get(&p, good[i].key, buf, sizeof buf), 0);
        assert_string_equal(buf, good[i].canonical);
    }
    // Every key is covered above.
    for (size_t k = 0; k < world_params_key_count(); k++) {
        int found = 0;
        for (size_t i = 0; i < sizeof good / sizeof good[0]; i++)
            found |= !strcmp(good[i].key, world_params_key(k));
        assert_true(found);
    }
    char small[4];
    assert_int_equal(world_params_get(&p, "radius", small, sizeof small), -1);
    assert_int_equal(world_params_get(&p, "nope", small, sizeof small), -1);
    og_error err = {{0}};
    assert_int_equal(world_params_set(&p, "nope", "1", &err), 1);
}

static void test_bad_values_rejected(void **state) {
    (void)state;
    static const char *const bad[][2] = {
        {"kind", "sphere"},
        {"kind", ""},
        {"generator", "8"},
        {"generator", "1.0"},
        {"generator", "fbm2"},
        {"seed", "12abc"},
        {"seed", "1.5"},
        {"seed", ""},
        {"seed", " 12"},
        {"seed", "9223372036854775808"},
        {"seed", "0x10"},
        {"octaves", "0"},
        {"octaves", "30.000001"},
        {"octaves", "nan"},
        {"octaves", "12abc"},
        {"w_factor", "1.5"},
        {"w_factor", "0"},
        {"exponent", "1"},
        {"exponent", "8.5"},
        {"max_height", "0"},
        {"max_height", "-1"},
        {"max_height", "1e300"},
        {"ocean_level", "inf"},
        {"ocean_level", "-inf"},
        {"ocean_level", "NaN"},
        {"ocean_level", "1e400"},
        {"ocean_level", "1,5"},
        {"radius", "0"},
        {"radius", "2e9"},
        {"omega", "infinity"},
        {"spacing", "0"},
        {"spacing", "1e6"},
        {"size", "-1"},
        {"size", "549755813889"},
        {"size", "100.5"},
        {"detail_ratio", "0"},
        {"detail_ratio", "65"},
        {"volume_ratio", "0"},
        {"volume_ratio", "9"},
        {"feature_size", "-1"},
        {"base_height", "nan"},
        {"roughness", "2.5"},
        {"smoothing", "1.01"},
        {"ridge_offset", "-0.1"},
        {"fault_count", "10001"},
        {"fault_count", "-1"},
        {"tiles", "a;b"},
        {"tiles", "a#b"},
        {"tiles", " lead"},
        {"tiles", "tab\there"},
        {"tiles_id", "0123"},
        {"tiles_id", "0123456789ABCDEF0123456789ABCDEF"},
        {"tiles_saved", "-2"},
        {"size_z", "-1"},
        {"size_z", "1.5"},
        {"geo_crs", "a;b"},
        {"geo_crs", "a#b"},
        {"geo_transform", "1,2,3"},
        {"geo_transform", "1,2,3,4,5,6,7"},
        {"geo_transform", "1,0,0,4,0,0"},
        {"geo_transform", "1,2,0,4,0,nan"},
    };
    world_params p, before;
    world_params_default(&p, WORLD_FLAT);
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        og_error err = {{0}};
        before = p;
        if (world_params_set(&p, bad[i][0], bad[i][1], &err) != -1)
            print_message("accepted %s = '%s'\n", bad[i][0], bad[i][1]);
        assert_int_equal(world_params_set(&p, bad[i][0], bad[i][1], &err), -1);
        assert_memory_equal(&p, &before, sizeof p);
        // The message names the key.
        assert_int_equal(strncmp(err.msg, bad[i][0], strlen(bad[i][0])), 0);
    }
    og_error err = {{0}};
    assert_int_equal(world_params_set(&p, "seed", "abc", &err), -1);
    assert_string_equal(err.msg, "seed: expected an integer, got 'abc'");
    // NaN and infinities are refused by every float key, in every spelling.
    static const char *const nonfinite[] = {"nan",  "NAN",       "-nan",  "inf",
                                            "-inf", "+Infinity", "1e999", "-1e999"};
    for (size_t k = 0; k < world_params_key_count(); k++) {
        const char *key = world_params_key(k);
        for (size_t i = 0; i < sizeof nonfinite / sizeof nonfinite[0]; i++) {
            if (!strcmp(key, "tiles") || !strcmp(key, "geo_crs")) continue;
            assert_int_equal(world_params_set(&p, key, nonfinite[i], &err), -1);
        }
    }
}

static void test_load_bad_number_keeps_default(void **state) {
    (void)state;
    const char *dir = test_tmpdir("params");
    const char *text = "# a flat world\n"
                       "seed = 12abc;\n"
                       "octaves = nan;\n"
                       "max_height = inf;\n"
                       "radius = ;\n"
                       "spacing = 4;\n"
                       "size = 1024;\n";
    world_params p, d;
    int errors = 0;
    messages m;
    char path[4200];
    assert_int_equal(
        load_text(dir, "w.world", text, strlen(text), &p, &errors, &m, path, sizeof path), 0);
    assert_int_equal(errors, 4);
    char want[4400];
    snprintf(want, sizeof want, "%s:2: error: seed: expected an integer, got '12abc'", path);
    assert_true(has_message(&m, want));
    snprintf(want, sizeof want, "%s:3: error: octaves:", path);
    assert_true(has_message_prefix(&m, want));
    snprintf(want, sizeof want, "%s:4: error: max_height:", path);
    assert_true(has_message_prefix(&m, want));
    snprintf(want, sizeof want, "%s:5: error: radius:", path);
    assert_true(has_message_prefix(&m, want));
    world_params_default(&d, WORLD_FLAT);
    assert_true(p.seed == d.seed);
    assert_true(p.octaves == d.octaves);
    assert_true(p.max_height == d.max_height);
    assert_true(p.radius == d.radius);
    assert_true(p.spacing == 4);
    assert_true(p.size == 1024);
    test_rmtree(dir);
}

static void test_load_unknown_key_and_syntax(void **state) {
    (void)state;
    const char *dir = test_tmpdir("params");
    const char *text = "seed = 5;\n"
                       "foo = 3;\n"
                       "octaves = 6\n"        // missing ';'
                       "just some words\n"    // no '='
                       " = 4;\n"              // no key
                       "spacing = 3; extra\n" // text after ';'
                       "max height = 9;\n"    // key is not one word
                       "seed = 6;  # again\n" // duplicate: last wins
                       "exponent = 2.5;\r\n"; // CRLF is fine
    world_params p;
    int errors = 0;
    messages m;
    char path[4200], want[4400];
    assert_int_equal(
        load_text(dir, "w.world", text, strlen(text), &p, &errors, &m, path, sizeof path), 0);
    assert_int_equal(errors, 5);
    snprintf(want, sizeof want, "%s:2: warning: unknown key 'foo'", path);
    assert_true(has_message(&m, want));
    snprintf(want, sizeof want, "%s:3: error: missing ';' after the value of 'octaves'", path);
    assert_true(has_message(&m, want));
    snprintf(want, sizeof want, "%s:4: error: expected 'key = value;', found no '='", path);
    assert_true(has_message(&m, want));
    snprintf(want, sizeof want, "%s:5: error:", path);
    assert_true(has_message_prefix(&m, want));
    snprintf(want, sizeof want, "%s:6: error: unexpected text after ';': 'extra'", path);
    assert_true(has_message(&m, want));
    snprintf(want, sizeof want, "%s:7: error:", path);
    assert_true(has_message_prefix(&m, want));
    snprintf(want, sizeof want,
             "%s:8: warning: duplicate key 'seed' (also set on line 1); the last one wins", path);
    assert_true(has_message(&m, want));
    // Reported in line order.
    for (size_t i = 1; i < m.count; i++) {
        int a = atoi(m.text[i - 1] + strlen(path) + 1), b = atoi(m.text[i] + strlen(path) + 1);
        assert_true(a <= b);
    }
    world_params d;
    world_params_default(&d, WORLD_FLAT);
    assert_true(p.seed == 6);
    assert_true(p.octaves == d.octaves);
    assert_true(p.spacing == d.spacing);
    assert_true(p.exponent == 2.5);
    test_rmtree(dir);
}

// An empty file (or only blanks and comments) is refused: Orogen never saves one, so it
// is damage (an interrupted copy), not a world of defaults.
static void test_load_empty_file(void **state) {
    (void)state;
    const char *dir = test_tmpdir("params");
    world_params p;
    int errors = -1;
    messages m;
    char path[4200];
    static const char *const empty[] = {"", " \n\n\t\n", "# only a comment\n\n   # and another\n"};
    for (size_t i = 0; i < sizeof empty / sizeof empty[0]; i++) {
        assert_int_equal(load_text(dir, "e.planet", empty[i], strlen(empty[i]), &p, &errors, &m,
                                   path, sizeof path),
                         -1);
        og_error err = {{0}};
        assert_int_equal(world_params_check_file(path, &err), -1);
        assert_non_null(strstr(err.msg, path));
        assert_non_null(strstr(err.msg, "empty"));
    }
    test_rmtree(dir);
}

// Issue 27, finding 3: a saved file cut short anywhere is never adopted: the seal (its
// last line) is missing, so it is reported naming the keys it lacks; a whole one, a
// hand-written one (no seal) and one edited by hand after saving load as before.
static void test_seal_detects_cut_short(void **state) {
    (void)state;
    const char *dir = test_tmpdir("params");
    world_params a;
    world_params_default(&a, WORLD_FLAT);
    assert_int_equal(world_params_set(&a, "generator", "ridged", NULL), 0);
    assert_int_equal(world_params_set(&a, "seed", "7", NULL), 0);
    char path[4200], why[1200];
    snprintf(path, sizeof path, "%s/s.world", dir);
    og_error err = {{0}};
    assert_int_equal(world_params_save(path, &a, &err), 0);
    size_t len = 0;
    char *text = test_read_file(path, &len);
    assert_int_equal(world_params_seal_check(text, len, why, sizeof why), 0);
    size_t cuts = 0;
    for (size_t cut = 1; cut < len; cut += 7, cuts++) {
        int rc = world_params_seal_check(text, cut, why, sizeof why);
        // Cut inside the header (before the sealed line) it reads as hand-written;
        // then the loader refuses it for having no key, or it lacks every key.
        if (rc == 0) { // refused whole: no line sets a key yet
            test_write_file(path, text, cut);
            world_params p;
            assert_int_equal(world_params_load(path, &p, NULL, NULL, NULL, &err), -1);
            continue;
        }
        assert_int_equal(rc, 1);
        assert_non_null(strstr(why, "cut short"));
        if (cut < (size_t)(strstr(text, "\nseed =") - text)) assert_non_null(strstr(why, "seed"));
    }
    assert_true(cuts > 300);
    // world_params_load_whole says so; world_params_load reports it as an error.
    test_write_file(path, text, len / 2);
    world_params p;
    int errors = 0;
    assert_int_equal(world_params_load_whole(path, &p, &errors, NULL, NULL, why, sizeof why, &err),
                     0);
    assert_non_null(strstr(why, "missing keys:"));
    assert_non_null(strstr(why, "tiles_id"));
    messages m = {0};
    assert_int_equal(world_params_load(path, &p, &errors, collect, &m, &err), 0);
    assert_int_equal(errors, 1);
    // Edited by hand after saving: read as it is, with a warning.
    char *edited = strdup(text);
    char *seed = strstr(edited, "\nseed = 7;");
    seed[8] = '8';
    test_write_file(path, edited, len);
    assert_int_equal(world_params_load_whole(path, &p, &errors, collect, &m, why, sizeof why, &err),
                     0);
    assert_string_equal(why, "");
    assert_int_equal(errors, 0);
    assert_int_equal(p.seed, 8);
    assert_non_null(strstr(m.text[m.count - 1], "changed after Orogen saved it"));
    free(edited);
    free(text);
    test_rmtree(dir);
}

static uint64_t rng_next(uint64_t *s) {
    *s ^= *s << 13, *s ^= *s >> 7, *s ^= *s << 17;
    return *s;
}

// Bytes that are not text are not a parameter file: refused whole, naming the file and
// the first bad byte, with nothing reported line by line and the parameters untouched.
static void test_load_binary_garbage(void **state) {
    (void)state;
    const char *dir = test_tmpdir("params");
    uint64_t rng = 0x9E3779B97F4A7C15u;
    static char buf[8192];
    char path[4200], want[4400];
    snprintf(path, sizeof path, "%s/garbage.world", dir);
    snprintf(want, sizeof want, "%s: not an Orogen world or planet parameter file (", path);
    for (int round = 0; round < 40; round++) {
        size_t len = 1 + (size_t)(rng_next(&rng) % sizeof buf);
        for (size_t i = 0; i < len; i++)
            buf[i] = (char)rng_next(&rng);
        buf[len / 2] = 0; // always at least one NUL
        world_params p;
        int errors = 0;
        messages m;
        og_error err = {{0}};
        test_write_file(path, buf, len);
        memset(&m, 0, sizeof m);
        assert_int_equal(world_params_load(path, &p, &errors, collect, &m, &err), -1);
        assert_int_equal(strncmp(err.msg, want, strlen(want)), 0);
        assert_int_equal(m.count, 0);
        assert_int_equal(world_params_check_file(path, &err), -1);
    }
    // One NUL among good lines is enough; the message says where it is.
    const char text[] = "seed = 3;\nab\0cd = 4;\x01\x02\nspacing = 7;\n";
    world_params p;
    int errors = 0;
    messages m;
    og_error err = {{0}};
    assert_int_equal(
        load_text(dir, "g.world", text, sizeof text - 1, &p, &errors, &m, path, sizeof path), -1);
    assert_int_equal(m.count, 0);
    snprintf(want, sizeof want,
             "%s: not an Orogen world or planet parameter file (byte 0x00 at line 2, column 3)",
             path);
    assert_int_equal(world_params_load(path, &p, &errors, NULL, NULL, &err), -1);
    assert_string_equal(err.msg, want);
    test_rmtree(dir);
}

// Text that is not UTF-8, or in which no line sets a key Orogen knows, is refused too;
// a file with one known key among unknown ones (seed 004's) loads, and so does one of
// only comments and blank lines (as an empty file does).
static void test_load_refuses_foreign_text(void **state) {
    (void)state;
    const char *dir = test_tmpdir("params");
    static const struct {
        const char *text, *why;
    } refused[] = {
        {"seed = 3;\n# caf\xe9 in Latin-1\n", "not UTF-8 text: byte 0xe9 at line 2, column 6"},
        {"seed = 3;\n\xc0\xaf = 1;\n", "not UTF-8 text: byte 0xc0 at line 2, column 1"},
        {"seed = 3;\vspacing = 2;\n", "byte 0x0b at line 1, column 10"},
        {"Dear diary,\ntoday I sculpted a mountain.\n", "no line has the form 'key = value;'"},
        {"colour = blue;\nname = mine;\n", "no line sets a known key; line 1 sets 'colour'"},
    };
    char path[4200], want[4400];
    for (size_t i = 0; i < sizeof refused / sizeof refused[0]; i++) {
        world_params p;
        int errors = 0;
        messages m;
        og_error err = {{0}};
        assert_int_equal(load_text(dir, "f.world", refused[i].text, strlen(refused[i].text), &p,
                                   &errors, &m, path, sizeof path),
                         -1);
        assert_int_equal(world_params_load(path, &p, &errors, NULL, NULL, &err), -1);
        snprintf(want, sizeof want, "%s: not an Orogen world or planet parameter file (%s)", path,
                 refused[i].why);
        assert_string_equal(err.msg, want);
    }
    static const char *const taken[] = {
        "caf\xc3\xa9 = 1;\nseed = 4;\n", // UTF-8, one unknown key and one known
        "seed = oops;\n",                // a known key with a bad value: loads, with an error
    };
    for (size_t i = 0; i < sizeof taken / sizeof taken[0]; i++) {
        world_params p;
        int errors = 0;
        messages m;
        assert_int_equal(load_text(dir, "t.world", taken[i], strlen(taken[i]), &p, &errors, &m,
                                   path, sizeof path),
                         0);
        og_error err = {{0}};
        assert_int_equal(world_params_check_file(path, &err), 0);
    }
    test_rmtree(dir);
}

static void test_load_long_line(void **state) {
    (void)state;
    const char *dir = test_tmpdir("params");
    size_t long_len = 100 * 1024;
    char *text = malloc(long_len + 64);
    assert_non_null(text);
    size_t n = (size_t)sprintf(text, "octaves = 3;\nradius = ");
    memset(text + n, '7', long_len);
    n += long_len;
    n += (size_t)sprintf(text + n, ";\nseed = 7;\n");
    world_params p;
    int errors = 0;
    messages m;
    char path[4200], want[4400];
    assert_int_equal(load_text(dir, "l.world", text, n, &p, &errors, &m, path, sizeof path), 0);
    assert_int_equal(errors, 1);
    snprintf(want, sizeof want, "%s:2: error: line is too long", path);
    assert_true(has_message_prefix(&m, want));
    assert_true(p.octaves == 3 && p.seed == 7);
    world_params d;
    world_params_default(&d, WORLD_FLAT);
    assert_true(p.radius == d.radius);
    free(text);
    test_rmtree(dir);
}

static void test_kind_inference(void **state) {
    (void)state;
    const char *dir = test_tmpdir("params");
    world_params p, d;
    int errors = 0;
    messages m;
    char path[4200];
    // Extension decides when the file is silent.
    assert_int_equal(
        load_text(dir, "a.planet", "seed = 1;\n", 10, &p, &errors, &m, path, sizeof path), 0);
    assert_int_equal(p.kind, WORLD_PLANET);
    assert_true(p.spacing == 100);
    assert_int_equal(load_text(dir, "a.txt", "seed = 1;\n", 10, &p, &errors, &m, path, sizeof path),
                     0);
    assert_int_equal(p.kind, WORLD_FLAT);
    // `kind` in the file wins, picks that kind's defaults, and other keys still override
    // (even when they come before it).
    const char *text = "max_height = 300;\nkind = planet;\n";
    assert_int_equal(
        load_text(dir, "b.world", text, strlen(text), &p, &errors, &m, path, sizeof path), 0);
    assert_int_equal(errors, 0);
    world_params_default(&d, WORLD_PLANET);
    d.max_height = 300;
    assert_params_equal(&p, &d);
    text = "kind = flat;\nseed = 9;\n";
    assert_int_equal(
        load_text(dir, "b.planet", text, strlen(text), &p, &errors, &m, path, sizeof path), 0);
    world_params_default(&d, WORLD_FLAT);
    d.seed = 9;
    assert_params_equal(&p, &d);
    // A bad kind is an error and the extension's kind stays.
    text = "kind = torus;\n";
    assert_int_equal(
        load_text(dir, "c.planet", text, strlen(text), &p, &errors, &m, path, sizeof path), 0);
    assert_int_equal(errors, 1);
    assert_int_equal(p.kind, WORLD_PLANET);
    test_rmtree(dir);
}

static void test_load_unreadable(void **state) {
    (void)state;
    const char *dir = test_tmpdir("params");
    char path[4200];
    world_params p;
    int errors = 0;
    og_error err = {{0}};
    snprintf(path, sizeof path, "%s/missing.world", dir);
    assert_int_equal(world_params_load(path, &p, &errors, NULL, NULL, &err), -1);
    assert_non_null(strstr(err.msg, path));
    // A folder is not a parameter file.
    assert_int_equal(world_params_load(dir, &p, &errors, NULL, NULL, &err), -1);
    assert_non_null(strstr(err.msg, dir));
    test_rmtree(dir);
}

static void test_validate(void **state) {
    (void)state;
    og_error err = {{0}};
    world_params p;
    world_params_default(&p, WORLD_PLANET);
    p.max_height = p.radius;
    assert_int_equal(world_params_validate(&p, &err), -1);
    assert_non_null(strstr(err.msg, "max_height"));
    // A planet's ocean_level is a radius: 0 .. radius + max_height.
    world_params_default(&p, WORLD_PLANET);
    p.ocean_level = p.radius + p.max_height + 1;
    assert_int_equal(world_params_validate(&p, &err), -1);
    assert_non_null(strstr(err.msg, "ocean_level: on a planet the sea's radius"));
    p.ocean_level = -1;
    assert_int_equal(world_params_validate(&p, &err), -1);
    p.ocean_level = p.radius - 10;
    assert_int_equal(world_params_validate(&p, &err), 0);
    assert_true(world_params_ocean_height(&p) == -10);
    world_params_default(&p, WORLD_FLAT);
    p.ocean_level = -5000; // flat: metres, any height
    assert_int_equal(world_params_validate(&p, &err), 0);
    assert_true(world_params_ocean_height(&p) == -5000);
    p.size = 1;
    assert_int_equal(world_params_validate(&p, &err), -1);
    assert_non_null(strstr(err.msg, "size"));
    p.size = 2;
    assert_int_equal(world_params_validate(&p, &err), 0);
    // Rectangular: rows of their own, 2 or more, on a bounded world only.
    p.size = 1201, p.size_z = 800;
    assert_int_equal(world_params_validate(&p, &err), 0);
    assert_int_equal(world_params_size_z(&p), 800);
    p.size_z = 1;
    assert_int_equal(world_params_validate(&p, &err), -1);
    assert_non_null(strstr(err.msg, "size_z"));
    p.size = 0, p.size_z = 800;
    assert_int_equal(world_params_validate(&p, &err), -1);
    p.size = 300, p.size_z = 0;
    assert_int_equal(world_params_size_z(&p), 300);
    // Fields filled directly get the same range checks as `set`.
    p.spacing = NAN;
    assert_int_equal(world_params_validate(&p, &err), -1);
    assert_non_null(strstr(err.msg, "spacing"));
    world_params_default(&p, WORLD_FLAT);
    p.generator = GEN_COUNT;
    assert_int_equal(world_params_validate(&p, &err), -1);
    assert_non_null(strstr(err.msg, "generator"));
}

// Awkward values every float key must carry through save and load bit for bit.
static void set_awkward(world_params *p) {
    world_params_default(p, WORLD_PLANET);
    p->generator = GEN_RIDGED;
    p->seed = INT64_MIN;
    p->octaves = 0.1;
    p->w_factor = 1.0 / 3.0;
    p->exponent = 2.0000000000000004;   // next double after 2
    p->max_height = 999999.99999999988; // largest double below 1e6
    p->ocean_level = -0.0;
    p->radius = 999999999.99999988; // largest double below 1e9
    p->omega = -1e-300;
    p->spacing = 0.30000000000000004;
    p->size = 12345;
    p->detail_ratio = 7;
    p->feature_size = 5e-324; // smallest subnormal
    p->base_height = 123456789.123456789;
    p->roughness = 0.1 + 0.2;
    p->smoothing = 0.7;
    p->ridge_offset = 1.9999999999999998;
    p->fault_count = 9999;
    strcpy(p->tiles, "store/planet one.tiles");
}

static void test_round_trip_exact(void **state) {
    (void)state;
    const char *dir = test_tmpdir("params");
    world_params a, b;
    set_awkward(&a);
    og_error err = {{0}};
    assert_int_equal(world_params_validate(&a, &err), 0);
    char *text = world_params_format(&a);
    assert_non_null(text);
    assert_int_equal(strncmp(text,
                             "# Orogen world parameters (kind planet). Syntax: key = value; '#' "
                             "starts a comment.\n",
                             80),
                     0);
    // Each key sits on its own line under a comment.
    for (size_t i = 0; i < world_params_key_count(); i++) {
        char needle[64];
        snprintf(needle, sizeof needle, "\n%s = ", world_params_key(i));
        const char *at = strstr(text, needle);
        assert_non_null(at);
        const char *prev_line = at - 1;
        while (prev_line > text && prev_line[-1] != '\n')
            prev_line--;
        assert_true(prev_line[0] == '#' && prev_line[1] == ' ');
    }
    char path[4200];
    snprintf(path, sizeof path, "%s/round.world", dir); // kind comes from the file
    assert_int_equal(world_params_save(path, &a, &err), 0);
    size_t len = 0;
    char *disk = test_read_file(path, &len);
    assert_non_null(disk);
    // The canonical text, with the line saying it is sealed after the header and the
    // seal (length and checksum) as the last line.
    const char *sealed = strstr(disk, "\n# Saved by Orogen: the last line seals the file");
    assert_non_null(sealed);
    size_t head = strcspn(text, "\n");
    assert_memory_equal(disk, text, head);
    const char *rest = strchr(sealed + 1, '\n') + 1;
    assert_memory_equal(rest, text + head + 1, strlen(text) - head - 1);
    char why[256];
    assert_int_equal(world_params_seal_check(disk, len, why, sizeof why), 0);
    assert_non_null(strstr(rest + strlen(text) - head - 1, "# end of file: "));
    int errors = -1;
    messages m = {0};
    assert_int_equal(world_params_load(path, &b, &errors, collect, &m, &err), 0);
    print_messages(&m);
    assert_int_equal(errors, 0);
    assert_int_equal(m.count, 0);
    assert_int_equal(b.kind, a.kind);
    assert_int_equal(b.generator, a.generator);
    assert_true(b.seed == a.seed && b.size == a.size);
    assert_true(b.detail_ratio == a.detail_ratio && b.fault_count == a.fault_count);
    const double *fa[] = {&a.octaves,      &a.w_factor,    &a.exponent,  &a.max_height,
                          &a.ocean_level,  &a.radius,      &a.omega,     &a.spacing,
                          &a.feature_size, &a.base_height, &a.roughness, &a.smoothing,
                          &a.ridge_offset};
    const double *fb[] = {&b.octaves,      &b.w_factor,    &b.exponent,  &b.max_height,
                          &b.ocean_level,  &b.radius,      &b.omega,     &b.spacing,
                          &b.feature_size, &b.base_height, &b.roughness, &b.smoothing,
                          &b.ridge_offset};
    for (size_t i = 0; i < sizeof fa / sizeof fa[0]; i++)
        assert_memory_equal(fa[i], fb[i], sizeof(double));
    assert_string_equal(a.tiles, b.tiles);
    char *again = world_params_format(&b);
    assert_string_equal(again, text);
    // Short forms where they are exact: 0.1 is written as 0.1, 2 as 2.
    assert_non_null(strstr(text, "\noctaves = 0.1;\n"));
    assert_non_null(strstr(text, "\nbase_height = 123456789.12345679;\n"));
    assert_non_null(strstr(text, "\nocean_level = -0;\n"));
    assert_non_null(strstr(text, "\nomega = -1e-300;\n"));
    free(again);
    free(disk);
    free(text);

    // Random finite doubles through get/set.
    uint64_t rng = 12345;
    for (int i = 0; i < 20000; i++) {
        uint64_t bits = rng_next(&rng);
        double v;
        memcpy(&v, &bits, sizeof v);
        if (!isfinite(v)) continue;
        char buf[64];
        a.ocean_level = v;
        assert_int_equal(world_params_get(&a, "ocean_level", buf, sizeof buf), 0);
        assert_int_equal(world_params_set(&b, "ocean_level", buf, &err), 0);
        assert_memory_equal(&a.ocean_level, &b.ocean_level, sizeof(double));
    }
    // Both default sets round trip too.
    for (int k = 0; k < 2; k++) {
        world_params_default(&a, (world_kind)k);
        snprintf(path, sizeof path, "%s/default%d.planet", dir, k);
        assert_int_equal(world_params_save(path, &a, &err), 0);
        assert_int_equal(world_params_load(path, &b, &errors, NULL, NULL, &err), 0);
        assert_int_equal(errors, 0);
        assert_params_equal(&a, &b);
    }
    test_rmtree(dir);
}

static void test_tiles_path(void **state) {
    (void)state;
    const char *tmp = test_tmpdir("params");
    char dir[4200], param[4300], out[4400], want[4400];
    snprintf(dir, sizeof dir, "%s", tmp);
    snprintf(param, sizeof param, "%s/world.world", dir);
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    og_error err = {{0}};

    assert_int_equal(world_params_tiles_path(&p, param, out, sizeof out, &err), 0);
    snprintf(want, sizeof want, "%s/world.tiles", dir);
    assert_string_equal(out, want);

    static const char *const ok[][2] = {
        {"sub/x.tiles", "sub/x.tiles"},
        {"./x.tiles", "x.tiles"},
        {"sub/../x.tiles", "x.tiles"},
        {"a//b/./c.tiles", "a/b/c.tiles"},
    };
    for (size_t i = 0; i < sizeof ok / sizeof ok[0]; i++) {
        assert_int_equal(world_params_set(&p, "tiles", ok[i][0], &err), 0);
        assert_int_equal(world_params_tiles_path(&p, param, out, sizeof out, &err), 0);
        snprintf(want, sizeof want, "%s/%s", dir, ok[i][1]);
        assert_string_equal(out, want);
    }
    static const char *const bad[] = {"../x.tiles", "/etc/x", "sub/../../x.tiles",
                                      "a/../..",    "sub/",   ".."};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        assert_int_equal(world_params_set(&p, "tiles", bad[i], &err), 0);
        err.msg[0] = 0;
        assert_int_equal(world_params_tiles_path(&p, param, out, sizeof out, &err), -1);
        snprintf(want, sizeof want, "'%s'", bad[i]);
        assert_non_null(strstr(err.msg, want));
        assert_int_equal(strncmp(err.msg, "tiles: ", 7), 0);
    }
    // A symbolic link inside the folder that points out of it is refused.
    char link[4400];
    snprintf(link, sizeof link, "%s/out", dir);
    assert_int_equal(symlink("/tmp", link), 0);
    assert_int_equal(world_params_set(&p, "tiles", "out/x.tiles", &err), 0);
    assert_int_equal(world_params_tiles_path(&p, param, out, sizeof out, &err), -1);
    assert_non_null(strstr(err.msg, "'out/x.tiles'"));
    // A link that stays inside is fine.
    char sub[4400], inner[4400];
    snprintf(sub, sizeof sub, "%s/real", dir);
    assert_int_equal(mkdir(sub, 0755), 0);
    snprintf(inner, sizeof inner, "%s/alias", dir);
    assert_int_equal(symlink("real", inner), 0);
    assert_int_equal(world_params_set(&p, "tiles", "alias/x.tiles", &err), 0);
    assert_int_equal(world_params_tiles_path(&p, param, out, sizeof out, &err), 0);
    // A parameter file given without a folder resolves beside it.
    assert_int_equal(world_params_set(&p, "tiles", "", &err), 0);
    assert_int_equal(world_params_tiles_path(&p, "earth.planet", out, sizeof out, &err), 0);
    assert_string_equal(out, "earth.tiles");
    // Too small an output buffer is an error, not a truncation.
    assert_int_equal(world_params_tiles_path(&p, param, out, 4, &err), -1);
    test_rmtree(dir);
}

static size_t count_entries(const char *dir) {
    DIR *d = opendir(dir);
    assert_non_null(d);
    size_t n = 0;
    for (struct dirent *e; (e = readdir(d));)
        if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) n++;
    closedir(d);
    return n;
}

static void test_atomic_write(void **state) {
    (void)state;
    const char *tmp = test_tmpdir("params");
    char dir[4200], path[4300], bad[4400];
    snprintf(dir, sizeof dir, "%s", tmp);
    snprintf(path, sizeof path, "%s/w.world", dir);
    og_error err = {{0}};
    assert_int_equal(param_file_write_atomic(path, "seed = 1;\n", 10, &err), 0);
    assert_int_equal(param_file_write_atomic(path, "seed = 2;\n", 10, &err), 0);
    size_t len;
    char *text = test_read_file(path, &len);
    assert_string_equal(text, "seed = 2;\n");
    free(text);
    assert_int_equal(count_entries(dir), 1); // no temporary left behind
    // Permissions of the replaced file are kept.
    assert_int_equal(chmod(path, 0600), 0);
    assert_int_equal(param_file_write_atomic(path, "seed = 3;\n", 10, &err), 0);
    struct stat st;
    assert_int_equal(stat(path, &st), 0);
    assert_int_equal(st.st_mode & 0777, 0600);

    // The parent "folder" is a regular file: fails even for root, names the path.
    snprintf(bad, sizeof bad, "%s/w.world/x.world", dir);
    err.msg[0] = 0;
    assert_int_equal(param_file_write_atomic(bad, "x", 1, &err), -1);
    assert_non_null(strstr(err.msg, bad));
    // The target is a folder.
    snprintf(bad, sizeof bad, "%s/folder", dir);
    assert_int_equal(mkdir(bad, 0755), 0);
    assert_int_equal(param_file_write_atomic(bad, "x", 1, &err), -1);
    assert_non_null(strstr(err.msg, bad));
    // A folder that does not exist.
    snprintf(bad, sizeof bad, "%s/none/x.world", dir);
    assert_int_equal(world_params_save(bad, &(world_params){0}, &err), -1);
    assert_non_null(strstr(err.msg, bad));
    text = test_read_file(path, &len);
    assert_string_equal(text, "seed = 3;\n");
    free(text);
    test_rmtree(dir);
}

// A full disk: a tiny tmpfs (needs root; skipped otherwise). The old file must survive
// byte for byte and no temporary may be left.
static void test_atomic_write_full_disk(void **state) {
    (void)state;
    const char *tmp = test_tmpdir("params-full");
    char dir[4200], path[4300];
    snprintf(dir, sizeof dir, "%s", tmp);
    if (mount("tmpfs", dir, "tmpfs", 0, "size=16k") != 0) {
        print_message("cannot mount a tmpfs (%s); full-disk case skipped\n", strerror(errno));
        test_rmtree(dir);
        skip();
    }
    snprintf(path, sizeof path, "%s/p.planet", dir);
    world_params p;
    world_params_default(&p, WORLD_PLANET);
    og_error err = {{0}};
    assert_int_equal(world_params_save(path, &p, &err), 0);
    size_t old_len;
    char *old = test_read_file(path, &old_len);
    assert_non_null(old);
    size_t big_len = 64 * 1024;
    char *big = malloc(big_len);
    memset(big, '#', big_len);
    err.msg[0] = 0;
    assert_int_equal(param_file_write_atomic(path, big, big_len, &err), -1);
    print_message("full disk: %s\n", err.msg);
    assert_non_null(strstr(err.msg, path));
    assert_non_null(strstr(err.msg, strerror(ENOSPC)));
    size_t now_len;
    char *now = test_read_file(path, &now_len);
    assert_int_equal(now_len, old_len);
    assert_memory_equal(now, old, old_len);
    assert_int_equal(count_entries(dir), 1);
    free(big);
    free(old);
    free(now);
    umount2(dir, MNT_DETACH);
    test_rmtree(dir);
}

static void test_param_file_parse(void **state) {
    (void)state;
    param_file pf;
    const char *text = "# comment\n"
                       "  key_one =  a value with spaces  ;  # trailing comment\n"
                       "empty = ;\n"
                       "eq = a=b;\n"
                       "\n"
                       "last = 1;"; // no final newline
    assert_int_equal(param_file_parse(text, strlen(text), &pf), 0);
    assert_int_equal(pf.diag_count, 0);
    assert_int_equal(pf.count, 4);
    assert_string_equal(pf.entries[0].key, "key_one");
    assert_string_equal(pf.entries[0].value, "a value with spaces");
    assert_int_equal(pf.entries[0].line, 2);
    assert_string_equal(pf.entries[1].value, "");
    assert_string_equal(pf.entries[2].value, "a=b");
    assert_string_equal(pf.entries[3].key, "last");
    assert_int_equal(pf.entries[3].line, 6);
    param_file_diag(&pf, PARAM_ERROR, 3, "custom %d", 7);
    assert_int_equal(pf.diag_count, 1);
    assert_string_equal(pf.diags[0].message, "custom 7");
    assert_int_equal(pf.diags[0].line, 3);
    param_file_free(&pf);

    // A UTF-8 byte order mark is not part of the first key.
    assert_int_equal(param_file_parse("\xEF\xBB\xBFseed = 4;\n", 13, &pf), 0);
    assert_int_equal(pf.diag_count, 0);
    assert_int_equal(pf.count, 1);
    assert_string_equal(pf.entries[0].key, "seed");
    param_file_free(&pf);

    // Thousands of bad lines do not produce thousands of diagnostics.
    size_t n = 5000 * 4;
    char *junk = malloc(n);
    for (size_t i = 0; i < n; i += 4)
        memcpy(junk + i, "xyz\n", 4);
    assert_int_equal(param_file_parse(junk, n, &pf), 0);
    assert_true(pf.diag_count > 10 && pf.diag_count <= 101);
    param_file_free(&pf);
    free(junk);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_seed004_planet_loads_unchanged),
        cmocka_unit_test(test_defaults_are_valid),
        cmocka_unit_test(test_key_table),
        cmocka_unit_test(test_set_get_every_key),
        cmocka_unit_test(test_bad_values_rejected),
        cmocka_unit_test(test_load_bad_number_keeps_default),
        cmocka_unit_test(test_load_unknown_key_and_syntax),
        cmocka_unit_test(test_load_empty_file),
        cmocka_unit_test(test_seal_detects_cut_short),
        cmocka_unit_test(test_load_binary_garbage),
        cmocka_unit_test(test_load_refuses_foreign_text),
        cmocka_unit_test(test_load_long_line),
        cmocka_unit_test(test_kind_inference),
        cmocka_unit_test(test_load_unreadable),
        cmocka_unit_test(test_validate),
        cmocka_unit_test(test_round_trip_exact),
        cmocka_unit_test(test_tiles_path),
        cmocka_unit_test(test_atomic_write),
        cmocka_unit_test(test_atomic_write_full_disk),
        cmocka_unit_test(test_param_file_parse),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
