// The editor window's parts (app/window*.c, app/viewport_drag.c) and the state they
// share: one window per process, driven from window_run on the UI thread.
#ifndef OROGEN_APP_WINDOW_INTERNAL_H
#define OROGEN_APP_WINDOW_INTERNAL_H

#include "app/camera_controls.h"
#include "app/dynamic_resolution.h"
#include "app/editor_ui.h"
#include "app/settings.h"
#include "app/tool_settings.h"
#include "app/ui_messages.h"
#include "app/viewport_drag_state.h"
#include "app/work_queue.h"
#include "editor/edit/recover.h"
#include "editor/params/world_grid.h"
#include "editor/tools/stamp.h"
#include "editor/cmd/tokenize.h"
#include "io/image_read.h"
#include "io/parse.h"
#include "renderer/gl_context.h"
#include "renderer/gl_target.h"
#include "renderer/material_textures.h"
#include "renderer/pick.h"
#include "renderer/planet_camera.h"
#include "renderer/ui_renderer.h"
#include "renderer/viewport.h"
#include "ui/ui.h"
#include "view/view_commands.h"

#include <epoxy/gl.h>
#include <GLFW/glfw3.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

// The movement keys: W S A D E Q.
enum { MOVE_KEY_COUNT = 6 };

typedef struct window_state {
    cmd_context *ctx;
    viewport *v;
    GLFWwindow *win;
    world_subscription *changes; // the world's change notifications (another world: new camera)
    camera_controls cc;
    double mouse_x, mouse_y; // window coordinates of the last motion event
    int mouse_in;
    viewport_drag_state drag; // viewport_drag.c's
    int dynamic_res;          // lower the resolution while moving (L)
    double sun_turned_at;     // when the rotating light last turned (seconds)
    int key_down[MOVE_KEY_COUNT];
    double key_since[MOVE_KEY_COUNT], key_held[MOVE_KEY_COUNT]; // seconds, see bank_keys
    int dirty;                                                  // something changed: draw a frame
    int settled;       // frames in a row with every level current
    int pending;       // levels (or layers) still waiting for tiles
    int render_failed; // the renderer refused this world (a planet): said once
    char title[512];
    char *session_text; // the session's commands (`history script`): ctx->session's text
    size_t session_len;
    char stdin_buf[8192];
    size_t stdin_len;
    int stdin_open;

    // The editor's UI over the viewport.
    ui_font *font;
    ui_context *ui;
    ui_renderer *uir;
    editor_ui ed;
    notices notices; // what failed for the UI, over the viewport until dismissed
    ui_input in;     // the latest pointer, buttons and keys (the busy UI's input)
    // Events for the editor's UI, queued as they come and handed out a frame's share at
    // a time (never lost or seen twice however slow a frame); frame_in is this frame's.
    ui_input_queue *queue;
    ui_input frame_in;
    int ui_dirty;      // input or state changed: build and draw the UI again
    ui_rect view_rect; // the viewport's part of the window (window coordinates)
    const char *gl_renderer;

    // The terrain image, reused while only the UI changes; rendered at a lower
    // resolution while the camera moves or a stroke is drawn (dynamic resolution).
    gl_target terrain;
    gl_target terrain_smooth; // the terrain image with its edges smoothed (full-size frames)
    int smooth_shown;         // compose shows terrain_smooth
    int smooth_owed;          // the image wants smoothing once the view is still
    int smooth_failed;        // the pass failed once (reported): not tried again
    int terrain_valid;
    float res_scale;
    double terrain_ms; // wall time of the last terrain frame
    double target_ms;  // frame-time goal while moving
    camera drawn_cam;  // what the terrain image shows
    render_settings drawn_settings;
    brush_cursor drawn_cursor;
    float drawn_scale;
    int drawn_w, drawn_h;
    int edited;          // an edit made an undo step this session: the first view's hint goes
    char cam_path[1024]; // the file of the world the camera looks at ("" unsaved): its camera
                         // is kept in the settings when the world is left
    int world_changed;   // change notifications since the terrain image
    double px_scale;     // framebuffer pixels per window unit (HiDPI)
    app_settings settings;
    char settings_path[4096], history_path[4096];

    // Every action's command text runs through this queue; long work runs off this
    // thread, and while it does the window shows its progress over the last frame.
    work_queue work;
    ui_context *busy_ui;  // the progress bar and Cancel button of long work
    double busy_drawn_ms; // when the progress was last drawn
    int close_after_work; // the close button was pressed while work ran
} window_state;

// --- window.c: the window's life, its queue and changes, picking helpers

void report(const char *what, const og_error *err);
// The terrain point under window position (x, y): the ray through that pixel marched
// against the heights the renderer holds (what is on screen), one coarse sample steps.
int pick_at(window_state *st, double x, double y, double hit[3]);
int in_view(const window_state *st, double x, double y);
// A point along the ray under (x, y) when no terrain is there: `dist` metres out.
void point_along_ray(window_state *st, double x, double y, double dist, double out[3]);
void reset_camera(window_state *st);
int ground_height(void *user, double x, double z, double *h);
// Queues text as an action that is echoed in the console.
void run_commands(window_state *st, const char *text, const char *label);
// Window coordinates to the UI's (framebuffer) pixels.
float ui_px(const window_state *st, double v);
// Framebuffer pixels per window unit, kept from the size callbacks: asking the window
// system on every pointer event would be a round trip to the X server each time.
void update_px_scale(window_state *st);
// Any change redraws; another world (new, load) gets its default camera unless a
// command placed the camera after it came (`new planet; camera_geo ...`).
void take_changes(window_state *st);
// The UI's fonts: DejaVu from fonts-dejavu-core ($OROGEN_FONT_DIR overrides the folder),
// at 15 px times the monitor's content scale times the user's UI scale.
ui_font *load_font(GLFWwindow *win, double user, og_error *err);

// --- window_input.c: GLFW events

void bank_keys(window_state *st);
// The banked time as a step for camera_controls_move; clears the bank.
move_keys take_keys(window_state *st);
int keys_held(const window_state *st);
// The close button asks first when there are unsaved changes.
void on_close(GLFWwindow *win);
void clear_frame_input(ui_input *in);
// Queues an event for the editor's UI (its time set now).
void queue_ui_event(window_state *st, ui_event e);
int ui_mods_of(int glfw_mods);
// After a UI frame: its key events the UI did not take are the viewport's shortcuts.
void keys_after_ui(window_state *st, const ui_input *in);
// Sets the window's GLFW callbacks (events go to st).
void window_input_attach(window_state *st);

// --- viewport_drag.c: the viewport's drags, mouse look, the camera mode

drag_kind viewport_drag_kind(const window_state *st);
// The right button is held for mouse look.
int viewport_looking(const window_state *st);
// While the brush is resized on screen: 1, with the point it is shown at and the radius
// and strength it would get; else 0.
int viewport_drag_resizing(const window_state *st, double at[3], double *radius, double *strength);
// The sculpting drag while one is drawn, else NULL.
sculpt_drag *viewport_drag_stroke(window_state *st);
// After queued work ran: a stroke that Esc or Cancel ended is over, and a planet drag's
// moves held during the job are picked now the world is free.
void viewport_drag_after_work(window_state *st);

sculpt_view sculpt_view_of(const window_state *st);
// Commits the drag's stroke (one undo step); a stroke that laid no dab leaves no step.
// The console shows the drag as one line rather than a line per mouse move.
void sculpt_end(window_state *st);
const char *tool_name(const brush *b);
// Fly, orbit or walk (C, View > Camera): seed 004's camera switch.
void set_camera_mode(window_state *st, int mode);
int camera_mode(const window_state *st);
// GLFW's button and cursor events over the window: they start, move and end drags.
void viewport_drag_button(GLFWwindow *win, int button, int action, int mods);
void viewport_drag_cursor(GLFWwindow *win, double x, double y);

// --- window_frame.c: the frame

void update_title(window_state *st);
// Brings the clipmaps up to date without waiting for tiles. Returns 1 when the picture
// changed (texels arrived), 0 when not, -1 when this world cannot be drawn.
int update_view(window_state *st);
const ui_draw_list *build_ui(window_state *st, int fw, int fh);
// The still, full-size terrain image with its edges smoothed into terrain_smooth: one
// pass over the image, never a new render (and never while moving, where it would
// cost every frame). Returns 1 when compose shows the smoothed image.
int smooth_terrain(window_state *st);
// Renders the terrain into its own image when something it shows changed: the camera,
// the world, the view settings, the brush cursor, the viewport's size, or newly
// arrived tiles. While the camera moves or a stroke is drawn the image is rendered
// smaller, sized to keep the frame near target_ms. Returns 1 when it rendered.
int render_terrain(window_state *st, int vw, int vh, int arrived);
// The window's picture: the terrain image in the viewport's rectangle, the UI over it.
void compose(window_state *st, const ui_draw_list *dl, int fw, int fh);
// While long work runs: the last frame with a progress bar and a Cancel button over
// its status bar, drawn at most ten times a second (none for work under 150 ms).
void draw_busy(window_state *st, const ui_draw_list *dl, int fw, int fh);

// --- window_commands.c: the window's commands

extern window_state *current_window;

#endif
