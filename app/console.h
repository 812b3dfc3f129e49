// The in-app console: scrollback of commands, their output and errors, and an input
// line with history (Up/Down, kept between runs by the settings) and Tab completion of
// command names. Drawn with the UI library; commands run through the command language.
#ifndef OROGEN_APP_CONSOLE_H
#define OROGEN_APP_CONSOLE_H

#include "app/notices.h"
#include "editor/cmd/commands.h"
#include "ui/ui.h"

#include <stddef.h>

#define CONSOLE_LINES 2000
#define CONSOLE_HISTORY 200
#define CONSOLE_INPUT 1024

typedef enum console_kind { CONSOLE_ECHO, CONSOLE_OUTPUT, CONSOLE_ERROR } console_kind;

typedef struct console {
    char *lines[CONSOLE_LINES]; // a ring
    console_kind kinds[CONSOLE_LINES];
    size_t first, count;
    char input[CONSOLE_INPUT];
    char *history[CONSOLE_HISTORY];
    size_t history_count;
    int history_at; // -1: editing a new line
    int open;
    int focus_input; // give the input line focus on the next frame
    // Where a typed line goes (the window's work queue); NULL: console_run at once.
    int (*submit)(void *user, const char *text);
    void *submit_user;
    // When set, a line run for the UI (not typed here) that fails is shown there too.
    notices *notices;
} console;

void console_init(console *c);
void console_free(console *c);
// Appends text (split at new lines) as lines of that kind.
void console_add(console *c, console_kind kind, const char *text);
// Runs a command line: echoes it, runs it, adds its output and errors. The output also
// goes to standard output and errors to standard error, as in batch mode.
int console_run(console *c, cmd_context *ctx, const char *text, const char *label);
// The input history, one command a line (missing file: none). Saving writes it
// atomically, creating the folder.
void console_load_history(console *c, const char *path);
int console_save_history(const console *c, const char *path, og_error *err);
// The console key (` or ~) opens or closes the console; key_typed: the key also went
// into the input line (it had the focus), and goes out of it again.
void console_toggle(console *c, int key_typed);
// Draws the console over r (scrollback above the input line). Enter runs the line.
void console_draw(console *c, ui_context *ui, cmd_context *ctx, ui_rect r);

#endif
