// What every command works on: the command context (the world, the next parameters,
// the brush, an open stroke, where output goes) and the shape of a command.
#ifndef OROGEN_EDITOR_CMD_CONTEXT_H
#define OROGEN_EDITOR_CMD_CONTEXT_H

#include "editor/tools/brush.h"
#include "editor/world/world.h"
#include "io/err.h"

#include <stdint.h>
#include <stdio.h>

typedef struct cmd_context {
    world *world;            // the current world (replaced by new/load)
    uint64_t world_serial;   // counts those replacements
    world_params next;       // parameters for the next `generate` (nparams)
    world_settings settings; // used for worlds created by new/load
    FILE *out;               // where commands print results
    int exit_requested;      // set by `exit`
    // Errors reported without failing the command (a parameter file that loaded with
    // bad lines): batch mode exits 1 when any were.
    int reported_errors;
    brush brush; // the current tool (`tool`), used by dab and stroke
    // Each tool's own settings, as it was last used (a tool picked again gets them back).
    brush tool_memory[BRUSH_TOOL_COUNT];
    unsigned tool_remembered; // bit t: tool_memory[t] holds settings
    int tool_size_per_tool;   // 0: radius and strength shared by all tools (tool memory=)
    int radius_chosen;        // a radius= was given: the view's auto_radius= no longer applies
    unsigned tool_serial;     // counts tools picked (`tool NAME`, or a tool=... that changes
                              // it): an editor's own tool modes (stamping) give way
    struct stroke *stroke;    // the stroke stroke_begin opened (NULL: none)
    FILE *record;             // when set, every command that succeeded is written here
    // The session's commands for `history script FILE` (the editor window keeps them
    // in memory: an open_memstream over session_text / session_len); NULL: none.
    FILE *session;
    char **session_text;
    size_t *session_len;
    int skip_record;         // set by a command that must not be recorded this time
    char resource_dir[4096]; // built-in resources (stamp library in resource_dir/stamps)
    char stamp_dir[4096];    // the user's stamp folder
    // A batch script's world made from a raster imports its parts as they are needed
    // (base_pending.h): defer_base allows it (batch mode; the window needs the whole
    // world at once), base_pending is the part not imported yet (NULL: none).
    int defer_base;
    struct base_pending *base_pending;
    // State of commands registered from outside (view/view_commands.c keeps
    // its viewport here: made by the first view command, or set by the window).
    // The command language never looks inside; app/ frees it.
    void *view_state;
} cmd_context;

typedef int (*cmd_fn)(cmd_context *ctx, int argc, char **argv, og_error *err);

// One command: its name, a usage line, a help text, the argument count it accepts
// (not counting the name) and the function that runs it.
typedef struct cmd_def {
    const char *name;
    const char *usage;
    const char *help;
    int min_args, max_args;
    cmd_fn run;
    int flags; // CMD_* below
} cmd_def;

enum {
    // Changes the world or the undo history: an open stroke is ended (committed) first,
    // so it stays one undo step. Read-only commands leave it open.
    CMD_ENDS_STROKE = 1,
    // A query of the editor window's own state, left out of recordings (--record): a
    // replay has no window to ask.
    CMD_NOT_RECORDED = 2,
    // Reads only the editor window's own state, never the world or the context: the
    // window may run it while long work owns both (cmd_job.h), on a context of its own.
    CMD_WHILE_BUSY = 4,
};

// A context on world w with the default tool (raise). The user's stamp folder is
// $OROGEN_STAMP_DIR, else $XDG_DATA_HOME/orogen/stamps, else ~/.local/share/orogen/stamps.
void cmd_context_init(cmd_context *ctx, world *w, const world_settings *settings, FILE *out,
                      const char *resource_dir);

#endif
