// Input that arrives while a job runs and that the window cannot act on then (a press on
// the viewport or a panel, typing, the wheel) waits here, in order, and is replayed
// through the same event handlers once the job has ended: no input is dropped, however
// long the work (issue 26). Presses on the busy UI (its Cancel button) and Esc, which
// cancels the work, act at once. Once one event waits, every later one waits behind it,
// so the order the user gave them in is kept.
#ifndef OROGEN_APP_DEFERRED_INPUT_H
#define OROGEN_APP_DEFERRED_INPUT_H

typedef struct GLFWwindow GLFWwindow;

#define DEFERRED_INPUT_MAX 4096 // beyond it, consecutive pointer moves merge into the last

typedef enum deferred_kind {
    DEFERRED_BUTTON,
    DEFERRED_CURSOR,
    DEFERRED_KEY,
    DEFERRED_CHAR,
    DEFERRED_SCROLL,
} deferred_kind;

typedef struct deferred_event {
    deferred_kind kind;
    int a, b, c; // button, action, mods | key, action, mods | codepoint
    double x, y; // the pointer | the wheel's offsets
} deferred_event;

// The window's GLFW handlers the events are replayed through.
typedef struct deferred_handlers {
    void (*button)(GLFWwindow *, int button, int action, int mods);
    void (*cursor)(GLFWwindow *, double x, double y);
    void (*key)(GLFWwindow *, int key, int scancode, int action, int mods);
    void (*character)(GLFWwindow *, unsigned codepoint);
    void (*scroll)(GLFWwindow *, double dx, double dy);
} deferred_handlers;

typedef struct deferred_input {
    deferred_handlers handlers;
    deferred_event events[DEFERRED_INPUT_MAX];
    int count;
    long lost;                  // events that found the queue full (reported once replayed)
    unsigned char held_live[8]; // a button pressed on the busy UI: its release is live too
    unsigned char held_late[8]; // a button whose press waits: its release waits behind it
} deferred_input;

// Queues an event; 0, or -1 (counted in lost) when the queue is full.
int deferred_input_push(deferred_input *d, deferred_event e);

#endif
