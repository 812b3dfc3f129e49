// The editor's keyboard shortcuts, in one table: the window's key handling looks keys up
// in it, the menus take their key labels from it, and the F1 help, the start-up banner
// and the README's key table (checked by tests/test_shortcuts.c) list its rows.
#ifndef OROGEN_APP_SHORTCUTS_H
#define OROGEN_APP_SHORTCUTS_H

// What a key does. SHORTCUT_RUN runs its text as a command; the others need the window
// (a dialog, the camera, the pointer, the current brush) and the window does them.
typedef enum shortcut_action {
    SHORTCUT_RUN,           // the command text in `arg`
    SHORTCUT_TOOL,          // the palette's tool named `arg` ("stamp" for the stamp tool)
    SHORTCUT_CONSOLE,       // open or close the console
    SHORTCUT_HELP,          // this table, as the F1 dialog
    SHORTCUT_RADIUS_DOWN,   // the brush's radius /1.15
    SHORTCUT_RADIUS_UP,     // x1.15
    SHORTCUT_STRENGTH_DOWN, // -0.05
    SHORTCUT_STRENGTH_UP,   // +0.05
    SHORTCUT_FOCUS,         // the camera onto the point under the pointer
    SHORTCUT_WALK,          // walk mode on or off
    SHORTCUT_RESET_VIEW,    // the default view
    SHORTCUT_NEXT_CAMERA,   // fly, orbit, walk
    SHORTCUT_LIGHT,         // the light turns or stops
    SHORTCUT_DYNAMIC_RES,   // dynamic resolution on or off
    SHORTCUT_MORE_LEVELS,   // one clipmap level more
    SHORTCUT_FEWER_LEVELS,  // one fewer
    SHORTCUT_SAVE,          // save where the world was saved (asks when it would lose work)
    SHORTCUT_SAVE_AS,       // the Save as dialog
    SHORTCUT_OPEN,          // the Open dialog
    SHORTCUT_NEW_FLAT,      // a new flat world (asks first about unsaved changes)
    SHORTCUT_QUIT,          // quit (asks first about unsaved changes)
    SHORTCUT_ACTION_COUNT
} shortcut_action;

// One key: its label as the menus and the help show it ("Ctrl+Shift+S", "F1", "~"),
// which is also where the key and its modifiers are read from, so they cannot disagree.
typedef struct shortcut_key {
    const char *label;
    shortcut_action action;
    const char *arg; // SHORTCUT_RUN: the command; SHORTCUT_TOOL: the tool's name
} shortcut_key;

enum { SHORTCUT_ROW_KEYS = 12 };

// One row of the README's key table: what the user does (keys or a mouse drag), what
// it does (the README's words), the F1 help's shorter line, and the keys it binds
// (none for a mouse row: those the viewport's drags handle).
typedef struct shortcut_row {
    const char *input;
    const char *meaning;
    const char *help;
    int banner; // also printed in the start-up banner
    shortcut_key keys[SHORTCUT_ROW_KEYS];
} shortcut_row;

enum { SHORTCUT_CTRL = 1, SHORTCUT_SHIFT = 2 };

int shortcut_row_count(void);
const shortcut_row *shortcut_row_at(int i);

// The key bound to (GLFW key code, SHORTCUT_CTRL/SHIFT), or NULL. Ctrl must match; a key
// bound without Shift also answers with Shift held when nothing is bound with it (as
// Shift+1 is 1), and Alt is ignored.
const shortcut_key *shortcut_find(int glfw_key, int mods);

// The label of the first key doing action (with arg, when given): "Ctrl+S"; NULL if none.
const char *shortcut_label(shortcut_action action, const char *arg);

// Reads a label into its GLFW key code and modifiers. Returns 0, or -1 for a label
// naming no key this table knows.
int shortcut_parse_label(const char *label, int *glfw_key, int *mods);

// The F1 help's line for row i ("G  walk mode ..."), in out.
const char *shortcut_help_line(int i, char *out, unsigned long size);

#endif
