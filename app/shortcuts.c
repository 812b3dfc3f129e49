// The keyboard shortcut table (see shortcuts.h). Rows are in the README's order.
#include "app/shortcuts.h"

#include <GLFW/glfw3.h>
#include <stdio.h>
#include <string.h>

#define RUN(label, command)                                                                        \
    { label, SHORTCUT_RUN, command }
#define TOOL(label, name)                                                                          \
    { label, SHORTCUT_TOOL, name }
#define KEY(label, action)                                                                         \
    { label, action, NULL }

static const shortcut_row rows[] = {
    {"left drag",
     "sculpt or paint with the current tool (one undo step per drag); the cursor shows the "
     "brush's radius and falloff, coloured by what a stroke would do (orange raise, blue "
     "lower, green smooth, yellow flatten/set/ramp/terrace, violet noise, cyan erosion, pink "
     "paint; Ctrl and Shift show their effect) and as opaque as its strength",
     "sculpt or paint with the current tool (one undo step per drag)",
     1,
     {{0}}},
    {"Ctrl + left drag, Shift + left drag",
     "the same stroke inverted (lower, sharpen, remove), or smoothing with the same brush size",
     "the stroke inverted, or smoothing with the same brush",
     0,
     {{0}}},
    {"Alt + left drag, middle drag",
     "orbit around the terrain point under the cursor",
     "orbit around the point under the pointer",
     1,
     {{0}}},
    {"right drag",
     "look around; while held: W/S/A/D fly, Q/E down/up, Shift x4, wheel changes the speed",
     "look; while held W A S D fly, Q E down/up, Shift faster, wheel sets the speed",
     1,
     {{0}}},
    {"wheel", "dolly toward the point under the cursor", "dolly toward the pointer", 1, {{0}}},
    {"G",
     "walk mode: W/S/A/D keep the eye 1.8 m above the ground",
     "walk mode (W A S D walk on the ground)",
     1,
     {KEY("G", SHORTCUT_WALK)}},
    {"F",
     "focus on the point under the cursor",
     "focus on the point under the pointer",
     1,
     {KEY("F", SHORTCUT_FOCUS)}},
    {"Home", "the default view", "reset the view", 1, {KEY("Home", SHORTCUT_RESET_VIEW)}},
    {"1 2 3 4 5",
     "shaded, wireframe, level colours, height colours, slope colours",
     "shaded, wireframe, levels, height, slope views",
     1,
     {RUN("1", "view shaded"), RUN("2", "view wireframe"), RUN("3", "view levels"),
      RUN("4", "view height"), RUN("5", "view slope")}},
    {"C",
     "camera: fly, orbit (right drag orbits the view's centre, Slartibartfast's \"homeworld\"), "
     "walk",
     "camera: fly, orbit (right drag orbits the view's centre), walk",
     0,
     {KEY("C", SHORTCUT_NEXT_CAMERA)}},
    {"R",
     "the light turns (`render sun_rotation=20` degrees a second) or stops",
     "the light turns or stops",
     0,
     {KEY("R", SHORTCUT_LIGHT)}},
    {"L",
     "dynamic resolution while moving on/off (`dynamic_resolution on|off`)",
     "dynamic resolution while moving on/off",
     0,
     {KEY("L", SHORTCUT_DYNAMIC_RES)}},
    {"Ctrl+= and Ctrl+-",
     "more / fewer clipmap levels (Slartibartfast's = and -, moved because - and = are "
     "strength)",
     "more / fewer levels of detail (Slartibartfast's = and -)",
     0,
     {KEY("Ctrl+=", SHORTCUT_MORE_LEVELS), KEY("Ctrl+-", SHORTCUT_FEWER_LEVELS)}},
    {"U J M T H P N K Y O I B",
     "raise, lower, smooth, flatten, set height, ramp, noise, terrace, thermal, hydraulic, "
     "paint, stamp (also in each palette button's tooltip)",
     "over the viewport: raise, lower, smooth, flatten, set height, ramp, noise, terrace, "
     "thermal, hydraulic, paint, stamp",
     0,
     {TOOL("U", "raise"), TOOL("J", "lower"), TOOL("M", "smooth"), TOOL("T", "flatten"),
      TOOL("H", "set"), TOOL("P", "ramp"), TOOL("N", "noise"), TOOL("K", "terrace"),
      TOOL("Y", "thermal"), TOOL("O", "hydraulic"), TOOL("I", "paint"), TOOL("B", "stamp")}},
    {"Ctrl+Z, Ctrl+Shift+Z (Ctrl+Y)",
     "undo, redo",
     "undo, redo",
     1,
     {RUN("Ctrl+Z", "undo"), RUN("Ctrl+Shift+Z", "redo"), RUN("Ctrl+Y", "redo")}},
    {"[ and ], - and =",
     "brush radius down/up (x1.15), strength down/up (0.05)",
     "brush radius down/up, strength down/up",
     0,
     {KEY("[", SHORTCUT_RADIUS_DOWN), KEY("]", SHORTCUT_RADIUS_UP),
      KEY("-", SHORTCUT_STRENGTH_DOWN), KEY("=", SHORTCUT_STRENGTH_UP)}},
    {"Alt + right drag",
     "resize the brush on screen: right/left its radius (1% a pixel), up/down its strength; "
     "applied as one `tool` command on release",
     "resize the brush on screen: right/left radius, up/down strength",
     0,
     {{0}}},
    {"Ctrl+S, Ctrl+Shift+S",
     "save, save as",
     "save, save as",
     1,
     {KEY("Ctrl+S", SHORTCUT_SAVE), KEY("Ctrl+Shift+S", SHORTCUT_SAVE_AS)}},
    {"Ctrl+N, Ctrl+O, Ctrl+Q",
     "new flat world, open, quit (asking first when there are unsaved changes)",
     "new flat world, open, quit",
     0,
     {KEY("Ctrl+N", SHORTCUT_NEW_FLAT), KEY("Ctrl+O", SHORTCUT_OPEN),
      KEY("Ctrl+Q", SHORTCUT_QUIT)}},
    {"~, F1, Esc",
     "console, keyboard shortcuts, close menus and dialogs (and cancel long work)",
     "console, this help, close menus and dialogs (and cancel long work)",
     0,
     {KEY("~", SHORTCUT_CONSOLE), KEY("F1", SHORTCUT_HELP)}},
};
#define ROW_COUNT ((int)(sizeof rows / sizeof rows[0]))

int shortcut_row_count(void) {
    return ROW_COUNT;
}

const shortcut_row *shortcut_row_at(int i) {
    return i >= 0 && i < ROW_COUNT ? &rows[i] : NULL;
}

// The keys a label can name besides letters and digits.
static const struct {
    const char *name;
    int key;
} named_keys[] = {{"Home", GLFW_KEY_HOME},      {"~", GLFW_KEY_GRAVE_ACCENT},
                  {"[", GLFW_KEY_LEFT_BRACKET}, {"]", GLFW_KEY_RIGHT_BRACKET},
                  {"-", GLFW_KEY_MINUS},        {"=", GLFW_KEY_EQUAL},
                  {"F1", GLFW_KEY_F1}};

int shortcut_parse_label(const char *label, int *glfw_key, int *mods) {
    *mods = 0;
    if (strncmp(label, "Ctrl+", 5) == 0 && label[5]) *mods |= SHORTCUT_CTRL, label += 5;
    if (strncmp(label, "Shift+", 6) == 0 && label[6]) *mods |= SHORTCUT_SHIFT, label += 6;
    if (label[0] >= 'A' && label[0] <= 'Z' && !label[1]) {
        *glfw_key = GLFW_KEY_A + (label[0] - 'A');
        return 0;
    }
    if (label[0] >= '0' && label[0] <= '9' && !label[1]) {
        *glfw_key = GLFW_KEY_0 + (label[0] - '0');
        return 0;
    }
    for (size_t i = 0; i < sizeof named_keys / sizeof named_keys[0]; i++)
        if (strcmp(label, named_keys[i].name) == 0) {
            *glfw_key = named_keys[i].key;
            return 0;
        }
    return -1;
}

// The key bound to exactly (glfw_key, mods), or NULL.
static const shortcut_key *find_exact(int glfw_key, int mods) {
    for (int i = 0; i < ROW_COUNT; i++)
        for (int j = 0; j < SHORTCUT_ROW_KEYS && rows[i].keys[j].label; j++) {
            int key, m;
            if (shortcut_parse_label(rows[i].keys[j].label, &key, &m) == 0 && key == glfw_key &&
                m == mods)
                return &rows[i].keys[j];
        }
    return NULL;
}

const shortcut_key *shortcut_find(int glfw_key, int mods) {
    mods &= SHORTCUT_CTRL | SHORTCUT_SHIFT;
    const shortcut_key *k = find_exact(glfw_key, mods);
    if (!k && (mods & SHORTCUT_SHIFT)) k = find_exact(glfw_key, mods & ~SHORTCUT_SHIFT);
    return k;
}

const char *shortcut_label(shortcut_action action, const char *arg) {
    for (int i = 0; i < ROW_COUNT; i++)
        for (int j = 0; j < SHORTCUT_ROW_KEYS && rows[i].keys[j].label; j++) {
            const shortcut_key *k = &rows[i].keys[j];
            if (k->action == action && (!arg || (k->arg && strcmp(k->arg, arg) == 0)))
                return k->label;
        }
    return NULL;
}

const char *shortcut_help_line(int i, char *out, unsigned long size) {
    const shortcut_row *r = shortcut_row_at(i);
    snprintf(out, size, "%s: %s", r ? r->input : "", r ? r->help : "");
    return out;
}
