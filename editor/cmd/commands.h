// The command language: one interpreter for batch scripts (`orogen --batch FILE`,
// `orogen -c 'cmd; cmd'`), the in-app console, the UI's actions and the tests.
// Commands are separated by newlines or `;`, arguments by blanks; "double quotes"
// keep blanks in an argument; `#` outside quotes starts a comment.
#ifndef OROGEN_EDITOR_COMMANDS_H
#define OROGEN_EDITOR_COMMANDS_H

#include "editor/cmd/cmd_script.h"
#include "editor/cmd/context.h"

// Adds commands defined outside the command language (the viewport's camera, view,
// render, screenshot and pick register themselves from view/view_commands.c, so the
// language knows no renderer). Call at start-up, before any cmd_run, from one
// thread. The table must outlive every context. Returns -1 (err set) when a name is
// already taken or the registry is full; nothing is added then.
int cmd_register(const cmd_def *defs, size_t count, og_error *err);

// Runs every command in text. Stops at the first failing command and returns -1 with
// err->msg = "label:line: error: message". label names the script ("-c" for -c).
// (Tokenises the text once, then cmd_script_run.)
int cmd_run(cmd_context *ctx, const char *text, size_t len, const char *label, og_error *err);
// Runs a tokenised script the same way (its label names it in errors).
int cmd_script_run(cmd_context *ctx, const cmd_script *s, og_error *err);

// 1 when every command in text is one of the language's own (and the text parses):
// such text may run on any thread (cmd_job.h). Registered commands (the renderer's, the
// window's) hold GL or window state and run on the thread that owns those.
int cmd_text_is_builtin(const char *text, size_t len);

// 1 when every command in text has all of flags (and the text parses).
int cmd_text_all_flagged(const char *text, size_t len, int flags);
// The same questions of a tokenised script (0 when it is malformed).
int cmd_script_is_builtin(const cmd_script *s);
int cmd_script_all_flagged(const cmd_script *s, int flags);

// Number of commands and their names, for completion and `cmdlist`.
size_t cmd_count(void);
const char *cmd_name(size_t i);

#endif
