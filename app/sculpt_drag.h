// The viewport's sculpting drag: stroke_begin when the button goes down, a typed
// stroke point per mouse move (work_queue_add_point), stroke_end on release, exactly
// as a script would run them (so a recording replays to the same terrain).
//
// The thread contract (work_queue.h): while a job runs, the UI thread reads neither
// the command context nor the world's tiles. A drag keeps what it needs from its start
// (the world's parameters, the tool); on flat worlds a move during a job is picked
// against what the renderer holds; on planets, whose picking reads the world, the
// move's window position is held and picked once the job has ended (in order, before
// the drag's stroke_end).
#ifndef OROGEN_APP_SCULPT_DRAG_H
#define OROGEN_APP_SCULPT_DRAG_H

#include "app/work_queue.h"
#include "renderer/viewport.h"
#include "ui/ui.h"

#define SCULPT_HELD_MAX 1024 // window positions held during a job (later ones replace the last)

typedef struct sculpt_drag {
    int active;          // the button is down
    int points;          // points queued for this drag
    int volume;          // a volume tool's drag: 3D points
    int face;            // a planet's stroke: the face its points are given on (else -1)
    world *world;        // the world it began on (read only when no job runs)
    world_params params; // and its parameters then
    brush brush;         // the tool then (a volume tool's depth and plane lock)
    double plane_y;      // a volume drag locked to a plane: its height
    double held[SCULPT_HELD_MAX][2];
    int held_count;
    int end_held; // released during a job with positions held: stroke_end follows them
    // The brush held still keeps dabbing (stroke_hold): the time the hold counts from,
    // restarted when the brush has moved a dab's spacing from where it was then, and
    // the last time the window saw the button still down (sculpt_drag_input_taken).
    double hold_from, seen_held_at;
    double hold_anchor[2];
    double (*clock)(void); // seconds; NULL: CLOCK_MONOTONIC (tests give their own)
} sculpt_drag;

// Where the viewport is in the window (window coordinates) and what it shows.
typedef struct sculpt_view {
    viewport *v;
    ui_rect rect;
} sculpt_view;

// Starts a drag at window position (x, y) (no job runs): smooth (Shift) smooths instead,
// invert (Ctrl) inverts the tool (for the volume tools: swaps fill and carve).
void sculpt_drag_begin(sculpt_drag *d, work_queue *q, cmd_context *ctx, sculpt_view view, double x,
                       double y, int smooth, int invert);
// The mouse moved to (x, y) during the drag (any time, a job running or not).
void sculpt_drag_to(sculpt_drag *d, work_queue *q, sculpt_view view, double x, double y);
// The window has taken the input that came so far (none waits) and the drag is still
// on: the button was held until now. Only this time counts as held, never the time a
// release is handled at (it may have waited behind a slow frame or a job).
void sculpt_drag_input_taken(sculpt_drag *d);
// Called every frame of a drag: once a dab's time has been seen held (spacing / 2
// seconds) since the hold began or was last queued, queues `stroke_hold SECONDS` so a
// brush held still keeps applying (unless the tool's hold=0; not ramp or the volume
// tools). 1 when it queued one.
int sculpt_drag_hold(sculpt_drag *d, work_queue *q);
// The button went up. Returns the drag's points (for the console's echo).
int sculpt_drag_end(sculpt_drag *d, work_queue *q);
// Picks and queues the positions held during a job (call when none runs).
void sculpt_drag_flush(sculpt_drag *d, work_queue *q, sculpt_view view);
// The stroke was cancelled (Esc, Cancel): the drag is over, held positions dropped.
void sculpt_drag_cancelled(sculpt_drag *d);

// A volume tool's brush centre for the mouse at (x, y): the picked surface pushed
// b->depth metres along the view ray or, during a drag locked to a plane (d active,
// not NULL), the ray's crossing of that plane. 0, or -1 when the ray never meets it.
int sculpt_volume_point(sculpt_drag *d, const brush *b, sculpt_view view, double x, double y,
                        const double hit[3], double out[3]);

// Planets: a picked point in face-local metres of face `face` (past its edges when the
// point lies on a neighbour: strokes may cross an edge). 0, or -1 when it points away.
int sculpt_face_metres(const world_params *p, int face, const double hit[3], double *x, double *z);

#endif
