// What the window holding the panels may ask of them (app/editor_ui.h): the console,
// the recent worlds, the clicks in the viewport a panel waits for, the stamp tool's
// preview and textures. The window never reads or writes the panels' state itself.
#include "app/editor_ui_internal.h"
#include "app/sculpt_drag.h"
#include "editor/params/world_grid.h"
#include "renderer/material_textures.h"
#include "renderer/ui_renderer.h"

void editor_ui_attach(editor_ui *e, work_queue *work, notices *n, editor_host host) {
    e->work = work;
    e->host = host;
    e->console.notices = n;
    e->console.submit = host.submit;
    e->console.submit_user = host.user;
}

console *editor_ui_console(editor_ui *e) {
    return &e->console;
}

void editor_ui_add_recent(editor_ui *e, const char *path) {
    remember_recent(e, path);
}

const char *editor_ui_recent(const editor_ui *e, int i) {
    return i >= 0 && i < e->recent_count ? e->recent[i] : NULL;
}

void editor_ui_offer_startup_recovery(editor_ui *e) {
    recover_offer_find_startup(&e->recovery);
}

void editor_ui_show_help(editor_ui *e) {
    e->show_help = 1;
}

void editor_ui_open_file(editor_ui *e, cmd_context *ctx, const char *path) {
    snprintf(e->open_path, sizeof e->open_path, "%.1023s", path);
    editor_ui_request(e, ctx, PENDING_OPEN);
}

editor_click editor_ui_click_wanted(const editor_ui *e) {
    if (e->picking_height) return EDITOR_CLICK_PICK_HEIGHT;
    if (e->shape_placing) return EDITOR_CLICK_SHAPE;
    if (e->stamps.active) return EDITOR_CLICK_STAMP;
    return EDITOR_CLICK_DRAG;
}

// The stamp tool's click: one stamp at the picked point (on a planet in that face's
// metres).
static int stamp_click(const editor_ui *e, const cmd_context *ctx, const double hit[3], char *cmd,
                       size_t len) {
    double x = hit[0], z = hit[2], s, t;
    int face = -1;
    const world_params *p = world_get_params(ctx->world);
    if (p->kind == WORLD_PLANET) {
        world_grid_direction_face(hit, &face, &s, &t);
        sculpt_face_metres(p, face, hit, &x, &z);
    }
    if (stamp_browser_command(&e->stamps, x, z, cmd, len) != 0) return 0;
    if (face >= 0) {
        size_t used = strlen(cmd);
        snprintf(cmd + used, len - used, " face=%d", face);
    }
    return 1;
}

double editor_ui_picked_height(const cmd_context *ctx, const double hit[3]) {
    const world_params *p = world_get_params(ctx->world);
    if (p->kind != WORLD_PLANET) return hit[1];
    return sqrt(hit[0] * hit[0] + hit[1] * hit[1] + hit[2] * hit[2]) - p->radius;
}

int editor_ui_viewport_click(editor_ui *e, const cmd_context *ctx, const double *hit, char *cmd,
                             size_t len, const char **label) {
    switch (editor_ui_click_wanted(e)) {
    case EDITOR_CLICK_PICK_HEIGHT: // the tool's height from the terrain (the Pick button)
        e->picking_height = 0;
        if (!hit) return 0;
        snprintf(cmd, len, "tool %s height=%.6g", current_tool(&ctx->brush),
                 editor_ui_picked_height(ctx, hit));
        *label = "pick";
        return 1;
    case EDITOR_CLICK_SHAPE: // a 3D shape: its clicks, then its command
        *label = "shape";
        return hit && editor_ui_shape_click(e, ctx, hit, cmd, len) == 1;
    case EDITOR_CLICK_STAMP:
        *label = "stamp";
        return hit && stamp_click(e, ctx, hit, cmd, len);
    case EDITOR_CLICK_DRAG:
        break;
    }
    return 0;
}

int editor_ui_stamp_active(const editor_ui *e) {
    return e->stamps.active;
}

double editor_ui_stamp_half_size(const editor_ui *e, double spacing) {
    return stamp_browser_half_size(&e->stamps, spacing);
}

void editor_ui_stamp_wheel(editor_ui *e, int ctrl, int shift, double dy) {
    stamp_browser *b = &e->stamps;
    if (ctrl) b->scale = fmin(20, fmax(0.1, b->scale * pow(1.1, dy)));
    if (shift) b->rotation = fmod(b->rotation + 5 * dy + 540, 360) - 180;
}

void editor_ui_stamp_dropped(editor_ui *e, const cmd_context *ctx) {
    stamp_browser_load(&e->stamps, ctx); // listed before, so the new one shows as new
    e->stamps.checked_at = 0;            // look at the folder again at once
}

// Lists the stamps again when the user's stamp folder changed (an image dropped on the
// window, stamp_add in the console, a file copied there by hand).
int editor_ui_refresh_stamps(editor_ui *e, const cmd_context *ctx, double now) {
    stamp_browser *b = &e->stamps;
    if (!stamp_browser_stale(b, ctx, now)) return 0;
    for (int i = 0; i < b->count; i++) {
        ui_renderer_delete_texture(b->entries[i].texture);
        b->entries[i].texture = 0;
    }
    stamp_browser_reload(b, ctx);
    return 1;
}

// Textures of the stamp thumbnails, once the browser has rendered them.
int editor_ui_upload_thumbnails(editor_ui *e) {
    stamp_browser *b = &e->stamps;
    if (!b->needs_upload) return 0;
    b->needs_upload = 0;
    for (int i = 0; i < b->count; i++)
        if (!b->entries[i].texture)
            b->entries[i].texture =
                ui_renderer_create_texture(STAMP_THUMB, STAMP_THUMB, b->entries[i].rgba);
    return 1;
}

// Swatches of the paint materials from the renderer's own procedural textures (a
// 64-pixel crop of each); "automatic" shows its rules' grass, rock and snow side by side.
void editor_ui_make_material_swatches(editor_ui *e) {
    enum { SWATCH = 64 };
    static unsigned char full[MATERIAL_TEXTURE_COUNT]
                             [MATERIAL_TEXTURE_SIZE * MATERIAL_TEXTURE_SIZE * 4];
    static unsigned char swatch[SWATCH * SWATCH * 4];
    for (int t = 0; t < MATERIAL_TEXTURE_COUNT; t++)
        material_texture_generate(t, full[t]);
    for (int m = 0; m < 8; m++) {
        for (int y = 0; y < SWATCH; y++)
            for (int x = 0; x < SWATCH; x++) {
                // Paint material m is texture m - 1 (sand .. moss); automatic shows three.
                int t = m > 0 ? m - 1 : (x < SWATCH / 3 ? 1 : x < 2 * SWATCH / 3 ? 2 : 3);
                const unsigned char *src =
                    full[t] + ((size_t)(y * 2) * MATERIAL_TEXTURE_SIZE + x * 2) * 4;
                unsigned char *dst = swatch + ((size_t)y * SWATCH + x) * 4;
                dst[0] = src[0], dst[1] = src[1], dst[2] = src[2], dst[3] = 255;
            }
        double sum[3] = {0, 0, 0};
        for (int i = 0; i < SWATCH * SWATCH; i++)
            for (int c = 0; c < 3; c++)
                sum[c] += swatch[i * 4 + c];
        e->material_colors[m] =
            UI_RGBA((int)(sum[0] / (SWATCH * SWATCH)), (int)(sum[1] / (SWATCH * SWATCH)),
                    (int)(sum[2] / (SWATCH * SWATCH)), 255);
        e->material_textures[m] = ui_renderer_create_texture(SWATCH, SWATCH, swatch);
    }
}
