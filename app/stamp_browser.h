// The stamp browser: every stamp (functional shapes, the built-in library, the user's
// folder) as a thumbnail the program renders itself (the shape as shaded relief),
// and the placement options of the stamp tool. Picking a stamp selects the stamp
// tool; a click in the viewport then runs `stamp NAME X Z ...` at the picked point.
#ifndef OROGEN_APP_STAMP_BROWSER_H
#define OROGEN_APP_STAMP_BROWSER_H

#include "editor/cmd/context.h"
#include "ui/ui.h"

#include <stdint.h>

#define STAMP_BROWSER_MAX 64
#define STAMP_THUMB 64 // thumbnail side, pixels

typedef struct stamp_entry {
    char name[128];
    char kind[16];         // functional, library, user
    double natural_half_m; // half the footprint at scale 1 on the coarse layer, metres
    uint8_t rgba[STAMP_THUMB * STAMP_THUMB * 4];
    uint32_t texture; // the renderer's texture (0 until uploaded)
} stamp_entry;

typedef struct stamp_browser {
    stamp_entry entries[STAMP_BROWSER_MAX];
    int count;
    int selected;           // -1: none
    int active;             // the stamp tool is the viewport's tool
    int open_request;       // show the browser's section (the palette's Stamp button)
    int loaded;             // the stamps are listed and their thumbnails rendered
    int needs_upload;       // thumbnails rendered since the panels last made textures of them
    long long folder_stamp; // the user folder's modification time when it was listed
    double checked_at;      // when that was last compared (seconds)
    double scale, rotation, intensity;
    int mode, layer, mirror;
} stamp_browser;

// Placement defaults; no stamps listed yet.
void stamp_browser_init(stamp_browser *b);
// Lists the stamps and renders their thumbnails (CPU; the panels upload them when
// needs_upload is set), once: on first use, as reading the library takes a moment.
void stamp_browser_load(stamp_browser *b, const cmd_context *ctx);
// The stamp tool becomes the viewport's tool (the palette's Stamp button): the stamps
// listed, the first selected when none is, the browser's section shown; or it ends
// (another tool was picked).
void stamp_browser_activate(stamp_browser *b, const cmd_context *ctx);
void stamp_browser_deactivate(stamp_browser *b);
// Whether the browser's section is to be shown (once: the request is taken).
int stamp_browser_take_open_request(stamp_browser *b);
// 1 when the user stamp folder changed since the stamps were listed (looked at once a
// second: `now` in seconds): the panels then free the thumbnails' textures and call
// stamp_browser_reload.
int stamp_browser_stale(stamp_browser *b, const cmd_context *ctx, double now);
// Lists the stamps again; a stamp that was not there before becomes the selected one
// and the stamp tool the current tool (an image dropped on the window).
void stamp_browser_reload(stamp_browser *b, const cmd_context *ctx);
// The dock section: thumbnails and placement options.
void stamp_browser_draw(stamp_browser *b, ui_context *ui, cmd_context *ctx, int *tool_changed);
// The command that places the selected stamp at (x, z) metres.
int stamp_browser_command(const stamp_browser *b, double x, double z, char *out, size_t size);
// Half the footprint of the selected stamp with the current options, metres.
double stamp_browser_half_size(const stamp_browser *b, double spacing);

#endif
