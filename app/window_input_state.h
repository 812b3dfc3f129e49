// The state of the window's input (app/window_input.c): the pointer, the UI's input and
// its queue, and the movement keys held. Only window_input.c touches it; the window's
// other parts ask through its functions (window_internal.h).
#ifndef OROGEN_APP_WINDOW_INPUT_STATE_H
#define OROGEN_APP_WINDOW_INPUT_STATE_H

#include "app/deferred_input.h"
#include "ui/ui.h"

// The movement keys: W S A D E Q.
enum { MOVE_KEY_COUNT = 6 };

typedef struct window_input_state {
    double mouse_x, mouse_y; // window coordinates of the last motion event
    int mouse_in;
    ui_input in; // the latest pointer, buttons and keys (the busy UI's input)
    // Events for the editor's UI, queued as they come and handed out a frame's share at
    // a time (never lost or seen twice however slow a frame); frame_in is this frame's.
    ui_input_queue *queue;
    ui_input frame_in;
    int key_down[MOVE_KEY_COUNT];
    double key_since[MOVE_KEY_COUNT], key_held[MOVE_KEY_COUNT]; // seconds, see bank_keys
    deferred_input deferred; // what came while a job ran, replayed after it
} window_input_state;

#endif
