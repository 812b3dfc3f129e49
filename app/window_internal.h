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
#include "app/window_frame_state.h"
#include "app/window_panels_state.h"
#include "app/window_input_state.h"
#include "app/window_run_state.h"
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

typedef struct window_state {
    // What every part shares: the command context and the viewport the window shows,
    // the GLFW window, the camera's controls, the queue every action's command text runs
    // through (long work runs off this thread; meanwhile the window shows its progress
    // over the last frame), the settings, and what is to be drawn again.
    cmd_context *ctx;
    viewport *v;
    GLFWwindow *win;
    camera_controls cc;
    work_queue work;
    app_settings settings;
    int dirty;    // something changed: draw a frame
    int ui_dirty; // input or state changed: build and draw the UI again

    // Each part's own state, touched only by its file (the others call its functions).
    window_run_state run;       // window.c: the window's life, the loop, changes, stdin
    window_input_state input;   // window_input.c: GLFW events, the UI's input queue
    viewport_drag_state drag;   // viewport_drag.c: drags, mouse look, the camera mode
    window_frame_state frame;   // window_frame.c: the terrain image, its resolution
    window_panels_state panels; // window_panels.c: the editor's panels over the viewport
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
// The close button was pressed while work ran: it is pressed again once the work ends.
void close_after_work(window_state *st);
// Any change redraws; another world (new, load) gets its default camera unless a
// command placed the camera after it came (`new planet; camera_geo ...`).
void take_changes(window_state *st);

// --- window_input.c: GLFW events, the pointer, the UI's input queue, movement keys

// The queue and the pointer where it is (before the first frame). Returns -1 out of memory.
int input_open(window_state *st);
void input_close(window_state *st);
// Where the pointer is before any motion event (the UI's first hover).
void input_first_pointer(window_state *st);
// The pointer in window coordinates (the last motion event's), and whether it is in the
// window; over a panel, menu or dialog of the UI.
void pointer_pos(const window_state *st, double *x, double *y);
int pointer_in_window(const window_state *st);
int pointer_over_ui(const window_state *st);
// A button or motion event: the UI's input and queue follow it; *dx, *dy get the motion.
void input_button(window_state *st, int button, int action, int mods);
void input_cursor(window_state *st, double x, double y, double *dx, double *dy);
// The UI frame's share of the queued events, and after the frame: the keys the UI did
// not take become the viewport's shortcuts. waiting gets how many events wait still.
const ui_input *input_frame(window_state *st, int wants_keyboard, size_t *waiting);
void input_frame_done(window_state *st);
// The busy UI's (progress and Cancel) input, and after its frame.
ui_input *input_busy_frame(window_state *st);
void input_busy_done(window_state *st);
void bank_keys(window_state *st);
// The banked time as a step for camera_controls_move; clears the bank.
move_keys take_keys(window_state *st);
int keys_held(const window_state *st);
// The close button asks first when there are unsaved changes.
void on_close(GLFWwindow *win);
// Queues an event for the editor's UI (its time set now).
void queue_ui_event(window_state *st, ui_event e);
int ui_mods_of(int glfw_mods);
// Sets the window's GLFW callbacks (events go to st).
void window_input_attach(window_state *st);

// --- busy_input.c: input that comes while a job runs waits and is replayed after it

// Each takes a GLFW event when it must wait (a job runs and the event is not for the busy
// UI or Esc): 1, and the handler returns at once.
int input_defer_button(window_state *st, int button, int action, int mods);
int input_defer_cursor(window_state *st, double x, double y);
int input_defer_key(window_state *st, int key, int action, int mods);
int input_defer_char(window_state *st, unsigned codepoint);
int input_defer_scroll(window_state *st, double dx, double dy);
// Once the job has ended: the events that waited, through the window's handlers, in order.
void input_replay_deferred(window_state *st);
// What the window has been given and not yet acted on: input events queued for the UI or
// held during a job, and commands queued behind the job running (ui_input_waiting).
size_t input_waiting(const window_state *st);

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

// The frame's state from the settings (frame-time goal while moving, ms), and its end.
void frame_open(window_state *st, double target_ms);
void frame_close(window_state *st);
// The world changed (an area, new parameters, another world): the image is redrawn.
void frame_world_changed(window_state *st);
// Another world or camera: a renderer that refused the last one tries again.
void frame_retry_render(window_state *st);
// Tiles are still arriving, or the image has not settled: frames go on.
int frame_unsettled(const window_state *st);
// A lowered or unsmoothed image owes a still, full-size frame.
int frame_owes_still(const window_state *st);
double frame_target_ms(const window_state *st);
// The still picture of window_screenshot: every tile in view arrived (at most ~60 s),
// the terrain rendered at full resolution and smoothed as a still view is; returns the
// UI's frame drawn over it.
const ui_draw_list *render_still(window_state *st, int fw, int fh);

void update_title(window_state *st);
// Brings the clipmaps up to date without waiting for tiles. Returns 1 when the picture
// changed (texels arrived), 0 when not, -1 when this world cannot be drawn.
int update_view(window_state *st);
// The frame's figures for the status bar: its time, resolution, levels waiting, the
// terrain point under the pointer, whether the resolution drops while moving.
void frame_status(window_state *st, editor_frame_info *info);
int frame_dynamic_resolution(const window_state *st);
void frame_set_dynamic_resolution(window_state *st, int on);
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

// --- window_panels.c: the editor's panels over the viewport

// The panels from the settings (recent worlds, UI scale), the console's history, the
// fonts, UI contexts and renderer; -1 with err when they cannot start. Closing frees
// whatever of them exists (GL context current).
int panels_open(window_state *st, og_error *err);
void panels_close(window_state *st);
// Into the settings: the recent worlds; the console's history to its file.
void panels_keep(window_state *st);
// The panels, asked through editor_ui.h's functions; where failures show for the UI.
editor_ui *panels_editor(window_state *st);
notices *panels_notices(window_state *st);
// The viewport's part of the window as the last UI frame laid it out (window units).
ui_rect view_rect(const window_state *st);
// An edit made an undo step: the first view's hint goes.
void panels_world_edited(window_state *st);
// The world now open (loaded, saved as, given on the command line) goes in front of
// File's recent worlds, however it was opened: a menu, a dialog or the console.
void panels_world_opened(window_state *st);
// The UI animates or waits on input; it took this frame's keys; it is under (x, y).
int panels_need_frame(const window_state *st);
int panels_took_keys(const window_state *st);
int panels_capture_point(const window_state *st, float x, float y);
// A widget of the progress bar of long work (its Cancel button) is under (x, y) (UI units).
int panels_busy_widget_at(const window_state *st, float x, float y);
// The UI scale (ui_scale): a new font at the new size.
int panels_set_scale(window_state *st, double scale, og_error *err);
// ui_widgets: the Viewport's rectangle, then every named widget of the last frame.
void panels_list_widgets(const window_state *st, FILE *out, const char *filter);
// Builds this frame's UI (running the commands its widgets ask for); sets the
// viewport's rectangle. fw, fh: the framebuffer's size.
const ui_draw_list *build_ui(window_state *st, int fw, int fh);
// While long work runs: its progress bar and Cancel button (Cancel cancels it).
const ui_draw_list *build_busy_ui(window_state *st, const char *what, double fraction,
                                  double elapsed_ms, int fw, int fh);
// The UI theme's background, and a UI frame drawn over the window.
ui_color panels_background(const window_state *st);
void panels_draw(window_state *st, const ui_draw_list *dl, int fw, int fh);

// --- window_commands.c: the window's commands

extern window_state *current_window;

#endif
