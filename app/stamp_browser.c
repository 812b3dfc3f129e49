#include "app/stamp_browser.h"

#include "editor/tools/stamp.h"
#include "editor/tools/stamp_shapes.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static const char *const modes[] = {"add", "subtract", "max", "min", "blend"};
static const char *const layers[] = {"coarse", "detail"};
static const char *const mirrors[] = {"none", "x", "z", "xz"};

// The stamp's value over a size x size grid covering its footprint.
static void sample_stamp(const stamp_source *s, int size, float *out) {
    for (int y = 0; y < size; y++)
        for (int x = 0; x < size; x++) {
            float u = (x + 0.5f) / size * 2 - 1, v = (y + 0.5f) / size * 2 - 1, h = 0;
            if (s->shape >= 0) {
                h = stamp_shape_value((stamp_shape)s->shape, u, v);
            } else if (s->pixels && s->width > 0 && s->height > 0) {
                int px = (int)((u + 1) * 0.5f * s->width), py = (int)((v + 1) * 0.5f * s->height);
                px = px < 0 ? 0 : px >= s->width ? s->width - 1 : px;
                py = py < 0 ? 0 : py >= s->height ? s->height - 1 : py;
                h = s->pixels[(size_t)py * s->width + px];
            }
            out[y * size + x] = h;
        }
}

// Shaded relief: a light from the north-west over the heights, tinted low to high.
static void relief(const float *h, int size, uint8_t *rgba) {
    float lo = h[0], hi = h[0];
    for (int i = 1; i < size * size; i++)
        lo = fminf(lo, h[i]), hi = fmaxf(hi, h[i]);
    float range = hi > lo ? hi - lo : 1;
    for (int y = 0; y < size; y++)
        for (int x = 0; x < size; x++) {
            int x0 = x > 0 ? x - 1 : x, x1 = x < size - 1 ? x + 1 : x;
            int y0 = y > 0 ? y - 1 : y, y1 = y < size - 1 ? y + 1 : y;
            float dx = (h[y * size + x1] - h[y * size + x0]) / range * size * 0.25f;
            float dy = (h[y1 * size + x] - h[y0 * size + x]) / range * size * 0.25f;
            float nl = 1.0f / sqrtf(dx * dx + dy * dy + 1.0f);
            float light = fmaxf(0.0f, (dx * 0.6f + dy * 0.6f + 0.53f) * nl); // from the NW
            float t = (h[y * size + x] - lo) / range;
            float r = 0.35f + 0.45f * t, g = 0.42f + 0.30f * t, b = 0.30f + 0.25f * t;
            float k = 0.35f + 0.85f * light;
            uint8_t *p = rgba + (y * size + x) * 4;
            p[0] = (uint8_t)fminf(255.0f, r * k * 255.0f);
            p[1] = (uint8_t)fminf(255.0f, g * k * 255.0f);
            p[2] = (uint8_t)fminf(255.0f, b * k * 255.0f);
            p[3] = 255;
        }
}

void stamp_browser_init(stamp_browser *b) {
    memset(b, 0, sizeof *b);
    b->selected = -1;
    b->scale = 1;
    b->intensity = 50;
}

static long long folder_time(const char *dir) {
    struct stat st;
    if (!dir[0] || stat(dir, &st) != 0) return 0;
    return (long long)st.st_mtim.tv_sec * 1000000000LL + st.st_mtim.tv_nsec;
}

int stamp_browser_stale(stamp_browser *b, const cmd_context *ctx, double now) {
    if (!b->loaded || now - b->checked_at < 1.0) return 0;
    b->checked_at = now;
    return folder_time(ctx->stamp_dir) != b->folder_stamp;
}

void stamp_browser_reload(stamp_browser *b, const cmd_context *ctx) {
    char before[STAMP_BROWSER_MAX][128];
    int n = b->count;
    char selected[128] = "";
    for (int i = 0; i < n; i++)
        snprintf(before[i], sizeof before[i], "%s", b->entries[i].name);
    if (b->selected >= 0) snprintf(selected, sizeof selected, "%s", b->entries[b->selected].name);
    b->count = 0;
    b->loaded = 0;
    b->selected = -1;
    stamp_browser_load(b, ctx);
    for (int i = 0; i < b->count; i++) {
        int known = 0;
        for (int k = 0; k < n && !known; k++)
            known = strcmp(before[k], b->entries[i].name) == 0;
        if (strcmp(b->entries[i].name, selected) == 0 && b->selected < 0) b->selected = i;
        if (!known && n > 0) { // new: it is what the user just added
            b->selected = i;
            b->active = 1;
            b->open_request = 1;
            break;
        }
    }
}

void stamp_browser_load(stamp_browser *b, const cmd_context *ctx) {
    if (b->loaded) return;
    b->loaded = 1;
    b->needs_upload = 1;
    b->folder_stamp = folder_time(ctx->stamp_dir);
    char *text = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&text, &len);
    if (!mem) return;
    stamp_list(ctx->resource_dir, ctx->stamp_dir, mem);
    fclose(mem);
    float *h = malloc(sizeof(float) * STAMP_THUMB * STAMP_THUMB);
    for (char *line = strtok(text, "\n"); line && h && b->count < STAMP_BROWSER_MAX;
         line = strtok(NULL, "\n")) {
        stamp_entry *e = &b->entries[b->count];
        if (sscanf(line, "%127s %15s", e->name, e->kind) != 2) continue;
        e->texture = 0; // made by the panels from rgba (editor_window.c)
        stamp_source s;
        og_error err;
        if (stamp_find(e->name, ctx->resource_dir, ctx->stamp_dir, &s, &err) != 0) continue;
        int samples =
            s.shape >= 0 ? STAMP_FUNCTIONAL_SAMPLES : (s.width > s.height ? s.width : s.height);
        e->natural_half_m = samples * 0.5;
        sample_stamp(&s, STAMP_THUMB, h);
        relief(h, STAMP_THUMB, e->rgba);
        stamp_source_free(&s);
        b->count++;
    }
    free(h);
    free(text);
}

double stamp_browser_half_size(const stamp_browser *b, double spacing) {
    if (b->selected < 0) return 0;
    double per = b->layer == 1 ? spacing / 4 : spacing; // detail samples (ratio 4 by default)
    return b->entries[b->selected].natural_half_m * per * b->scale;
}

int stamp_browser_command(const stamp_browser *b, double x, double z, char *out, size_t size) {
    if (b->selected < 0) return -1;
    int n = snprintf(out, size,
                     "stamp %s %.17g %.17g scale=%.6g rot=%.6g intensity=%.6g mode=%s "
                     "layer=%s mirror=%s",
                     b->entries[b->selected].name, x, z, b->scale, b->rotation, b->intensity,
                     modes[b->mode], layers[b->layer], mirrors[b->mirror]);
    return n > 0 && (size_t)n < size ? 0 : -1;
}

void stamp_browser_draw(stamp_browser *b, ui_context *ui, cmd_context *ctx, int *tool_changed) {
    stamp_browser_load(b, ctx);
    float cols[3] = {0, 0, 0};
    float cell = ui_em(ui, 4.2f);
    ui_push_scope(ui, "Stamps");
    for (int i = 0; i < b->count; i++) {
        if (i % 3 == 0) ui_row(ui, 3, cols, cell);
        char label[160];
        snprintf(label, sizeof label, "%s##stamp", b->entries[i].name);
        if (ui_image_button(ui, label, b->entries[i].texture, b->active && b->selected == i)) {
            b->selected = i;
            b->active = 1;
            *tool_changed = 1;
        }
        char tip[256];
        snprintf(tip, sizeof tip, "%s (%s): click it, then click in the viewport to place it",
                 b->entries[i].name, b->entries[i].kind);
        ui_tooltip(ui, tip);
    }
    ui_pop_scope(ui);
    ui_row(ui, 1, NULL, 0);
    ui_slider(ui, "Scale##stamp", &b->scale, 0.1, 20, "%.2f x");
    ui_tooltip(ui, "Size against the stamp's natural size (Ctrl+wheel over the viewport)");
    ui_slider(ui, "Rotation##stamp", &b->rotation, -180, 180, "%.0f deg");
    ui_tooltip(ui, "Degrees, counter-clockwise seen from above (Shift+wheel over the viewport)");
    ui_slider(ui, "Intensity##stamp", &b->intensity, -500, 500, "%.1f m");
    ui_tooltip(ui, "Metres of height where the stamp's value is 1");
    ui_combo(ui, "Mode##stamp", &b->mode, modes, 5);
    ui_tooltip(ui, "add, subtract, max (raise from the ground), min (carve in), blend");
    ui_combo(ui, "Layer##stamp", &b->layer, layers, 2);
    ui_tooltip(ui, "coarse: the terrain's shape; detail: fine relief");
    ui_combo(ui, "Mirror##stamp", &b->mirror, mirrors, 4);
    ui_tooltip(ui, "Mirror the stamp across its x or z axis");
}

void stamp_browser_activate(stamp_browser *b, const cmd_context *ctx) {
    stamp_browser_load(b, ctx);
    if (b->selected < 0 && b->count > 0) b->selected = 0;
    b->active = b->selected >= 0;
    b->open_request = 1;
}

void stamp_browser_deactivate(stamp_browser *b) {
    b->active = 0;
}

int stamp_browser_take_open_request(stamp_browser *b) {
    int asked = b->open_request;
    b->open_request = 0;
    return asked;
}
