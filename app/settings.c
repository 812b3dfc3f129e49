#include "app/settings.h"

#include "io/param_file.h"
#include "io/parse.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

void app_settings_default(app_settings *s) {
    memset(s, 0, sizeof *s);
    s->width = 1280;
    s->height = 800;
    s->ui_scale = 1.0;
    s->field_of_view = 60.0;
    s->frame_target_ms = 50.0;
    s->fly_speed = 50.0;
    s->dynamic_lod = 1;
    s->lod_pixels = 6.0;
}

void app_settings_path(char *buf, size_t size, const char *file) {
    const char *xdg = getenv("XDG_CONFIG_HOME"), *home = getenv("HOME");
    if (xdg && *xdg)
        snprintf(buf, size, "%s/orogen/%s", xdg, file);
    else if (home && *home)
        snprintf(buf, size, "%s/.config/orogen/%s", home, file);
    else if (size)
        buf[0] = 0;
}

static void warn(const char *path, int line, const char *msg) {
    fprintf(stderr, "%s:%d: warning: %s (the default is kept)\n", path, line, msg);
}

static void read_int(const char *path, const param_entry *e, int lo, int hi, int *out) {
    double v;
    og_error err;
    if (parse_integer_in(e->value, e->key, lo, hi, &v, &err) != 0)
        warn(path, e->line, err.msg);
    else
        *out = (int)v;
}

static void read_number(const char *path, const param_entry *e, double lo, double hi, double *out) {
    double v;
    og_error err;
    if (parse_number_in(e->value, e->key, lo, hi, &v, &err) != 0)
        warn(path, e->line, err.msg);
    else
        *out = v;
}

// "X Y Z YAW PITCH PATH": five numbers, then the absolute path (spaces allowed).
static void read_camera(const char *path, const param_entry *e, app_settings *s) {
    app_world_camera c;
    memset(&c, 0, sizeof c);
    int used = 0;
    if (sscanf(e->value, "%lf %lf %lf %lf %lf %n", &c.pose[0], &c.pose[1], &c.pose[2], &c.pose[3],
               &c.pose[4], &used) != 5 ||
        e->value[used] != '/') {
        warn(path, e->line, "world_camera: expected X Y Z YAW PITCH /PATH");
        return;
    }
    for (int i = 0; i < 5; i++)
        if (!isfinite(c.pose[i])) {
            warn(path, e->line, "world_camera: a number is not finite");
            return;
        }
    if (s->camera_count >= SETTINGS_CAMERAS) return;
    snprintf(c.path, sizeof c.path, "%s", e->value + used);
    s->cameras[s->camera_count++] = c;
}

void app_settings_load(app_settings *s, const char *path) {
    param_file pf = {0};
    og_error err;
    if (!path[0]) return;
    struct stat st;
    if (stat(path, &st) != 0 && errno == ENOENT) return; // first run
    if (param_file_read(path, &pf, &err) != 0) {
        fprintf(stderr, "%s: warning: %s (defaults used)\n", path, err.msg);
        return;
    }
    for (size_t i = 0; i < pf.diag_count; i++)
        warn(path, pf.diags[i].line, pf.diags[i].message);
    for (size_t i = 0; i < pf.count; i++) {
        const param_entry *e = &pf.entries[i];
        if (strcmp(e->key, "width") == 0)
            read_int(path, e, 320, 16384, &s->width);
        else if (strcmp(e->key, "height") == 0)
            read_int(path, e, 240, 16384, &s->height);
        else if (strcmp(e->key, "x") == 0)
            read_int(path, e, -100000, 100000, &s->x), s->has_position = 1;
        else if (strcmp(e->key, "y") == 0)
            read_int(path, e, -100000, 100000, &s->y), s->has_position = 1;
        else if (strcmp(e->key, "maximized") == 0)
            read_int(path, e, 0, 1, &s->maximized);
        else if (strcmp(e->key, "enable_fullscreen") == 0)
            read_int(path, e, 0, 1, &s->fullscreen);
        else if (strcmp(e->key, "ui_scale") == 0)
            read_number(path, e, 0.5, 4, &s->ui_scale);
        else if (strcmp(e->key, "field_of_view") == 0)
            read_number(path, e, 1, 170, &s->field_of_view);
        else if (strcmp(e->key, "frame_target_ms") == 0)
            read_number(path, e, 5, 1000, &s->frame_target_ms);
        else if (strcmp(e->key, "fly_speed") == 0)
            read_number(path, e, 0.01, 1e7, &s->fly_speed);
        else if (strcmp(e->key, "enable_dynamic_LOD") == 0)
            read_int(path, e, 0, 1, &s->dynamic_lod);
        else if (strcmp(e->key, "lod_pixels") == 0)
            read_number(path, e, 1, 64, &s->lod_pixels);
        else if (strcmp(e->key, "tool") == 0)
            snprintf(s->tool, sizeof s->tool, "%.31s", e->value);
        else if (strncmp(e->key, "tool_", 5) == 0) {
            if (s->tool_count < SETTINGS_TOOLS && e->key[5])
                snprintf(s->tools[s->tool_count++], sizeof s->tools[0], "%.40s %.700s", e->key + 5,
                         e->value);
        } else if (strncmp(e->key, "world_camera_", 13) == 0) {
            read_camera(path, e, s);
        } else if (strncmp(e->key, "recent_", 7) == 0) {
            if (s->recent_count < SETTINGS_RECENT && e->value[0])
                snprintf(s->recent[s->recent_count++], sizeof s->recent[0], "%s", e->value);
        } else {
            char msg[300];
            snprintf(msg, sizeof msg, "unknown setting '%s'", e->key);
            warn(path, e->line, msg);
        }
    }
    param_file_free(&pf);
}

int app_settings_make_folders(const char *path) {
    char dir[4096];
    snprintf(dir, sizeof dir, "%s", path);
    for (char *p = dir + 1; *p; p++) {
        if (*p != '/') continue;
        *p = 0;
        if (mkdir(dir, 0755) != 0 && errno != EEXIST) return -1;
        *p = '/';
    }
    return 0;
}

int app_settings_save(const app_settings *s, const char *path, og_error *err) {
    if (!path[0]) return og_error_set(err, "no settings folder (HOME is not set)");
    if (app_settings_make_folders(path) != 0)
        return og_error_set(err, "%s: cannot create its folder: %s", path, strerror(errno));
    static char text[65536]; // the UI thread's, once at close
    char num[64];
    size_t n = 0;
#define PUT(...) n += (size_t)snprintf(text + n, n < sizeof text ? sizeof text - n : 0, __VA_ARGS__)
    PUT("# Orogen's editor settings (written when the editor closes).\n");
    PUT("width = %d;\nheight = %d;\n", s->width, s->height);
    if (s->has_position) PUT("x = %d;\ny = %d;\n", s->x, s->y);
    PUT("maximized = %d;\nenable_fullscreen = %d;\n", s->maximized, s->fullscreen);
    parse_format_f64(num, sizeof num, s->ui_scale);
    PUT("ui_scale = %s;\n", num);
    parse_format_f64(num, sizeof num, s->field_of_view);
    PUT("field_of_view = %s;\n", num);
    parse_format_f64(num, sizeof num, s->frame_target_ms);
    PUT("frame_target_ms = %s;\n", num);
    parse_format_f64(num, sizeof num, s->fly_speed);
    PUT("fly_speed = %s;\n", num);
    PUT("enable_dynamic_LOD = %d;\n", s->dynamic_lod);
    parse_format_f64(num, sizeof num, s->lod_pixels);
    PUT("lod_pixels = %s;\n", num);
    for (int i = 0; i < s->recent_count; i++)
        if (!strpbrk(s->recent[i], ";#\n")) PUT("recent_%d = %s;\n", i, s->recent[i]);
    if (s->tool[0] && !strpbrk(s->tool, ";#\n= ")) PUT("tool = %s;\n", s->tool);
    for (int i = 0; i < s->tool_count; i++) {
        const char *space = strchr(s->tools[i], ' ');
        if (space && !strpbrk(s->tools[i], ";#\n"))
            PUT("tool_%.*s = %s;\n", (int)(space - s->tools[i]), s->tools[i], space + 1);
    }
    for (int i = 0; i < s->camera_count; i++) {
        const double *c = s->cameras[i].pose;
        if (!strpbrk(s->cameras[i].path, ";#\n"))
            PUT("world_camera_%d = %.17g %.17g %.17g %.17g %.17g %s;\n", i, c[0], c[1], c[2], c[3],
                c[4], s->cameras[i].path);
    }
#undef PUT
    if (n >= sizeof text) return og_error_set(err, "%s: settings too long", path);
    return param_file_write_atomic(path, text, n, err);
}

// path as an absolute path (the file resolved when it exists, else joined to the
// working directory), so a recent file opens from wherever the editor starts next.
void app_absolute_path(const char *path, char *out, size_t size) {
    char *real = realpath(path, NULL);
    if (real) {
        snprintf(out, size, "%s", real);
        free(real);
        return;
    }
    char cwd[4096];
    size_t used = 0;
    if (path[0] != '/' && getcwd(cwd, sizeof cwd) && strlen(cwd) + 1 < size) {
        used = strlen(cwd);
        memcpy(out, cwd, used);
        out[used++] = '/';
    }
    snprintf(out + used, size - used, "%s", path);
}

void app_settings_fit_to_screen(app_settings *s, int ax, int ay, int aw, int ah) {
    if (aw <= 0 || ah <= 0) return;
    if (s->width > aw || s->height > ah) {
        s->width = s->width > aw ? aw : s->width;
        s->height = s->height > ah ? ah : s->height;
        s->maximized = 1;
        s->x = ax, s->y = ay, s->has_position = 1;
    }
    if (s->has_position &&
        (s->x < ax || s->y < ay || s->x + s->width > ax + aw || s->y + s->height > ay + ah))
        s->has_position = 0;
}

void app_settings_add_recent(app_settings *s, const char *path) {
    if (!path || !path[0]) return;
    char keep[1024];
    app_absolute_path(path, keep, sizeof keep);
    int n = 0;
    char list[SETTINGS_RECENT][1024];
    snprintf(list[n++], sizeof list[0], "%s", keep);
    for (int i = 0; i < s->recent_count && n < SETTINGS_RECENT; i++)
        if (strcmp(s->recent[i], keep) != 0)
            snprintf(list[n++], sizeof list[0], "%s", s->recent[i]);
    memcpy(s->recent, list, sizeof list);
    s->recent_count = n;
}

void app_settings_put_camera(app_settings *s, const char *path, const double pose[5]) {
    if (!path || !path[0]) return;
    app_world_camera list[SETTINGS_CAMERAS];
    int n = 1;
    app_absolute_path(path, list[0].path, sizeof list[0].path);
    memcpy(list[0].pose, pose, sizeof list[0].pose);
    for (int i = 0; i < s->camera_count && n < SETTINGS_CAMERAS; i++)
        if (strcmp(s->cameras[i].path, list[0].path) != 0) list[n++] = s->cameras[i];
    memcpy(s->cameras, list, (size_t)n * sizeof list[0]);
    s->camera_count = n;
}

int app_settings_find_camera(const app_settings *s, const char *path, double pose[5]) {
    if (!path || !path[0]) return -1;
    char want[1024];
    app_absolute_path(path, want, sizeof want);
    for (int i = 0; i < s->camera_count; i++)
        if (strcmp(s->cameras[i].path, want) == 0) {
            memcpy(pose, s->cameras[i].pose, 5 * sizeof pose[0]);
            return 0;
        }
    return -1;
}
