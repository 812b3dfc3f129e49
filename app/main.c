// orogen: the command line. Batch mode (--batch FILE, -c 'cmd; cmd') runs the
// command language with no window and no GL; interactive mode opens the editor
// window on the default world (or the one named), with the console on stdin.
#include "app/ui_messages.h"
#include "app/window.h"
#include "app/world_warnings.h"
#include "view/view_commands.h"
#include "renderer/viewport.h"
#include "editor/cmd/base_pending.h"
#include "editor/cmd/commands.h"
#include "editor/cmd/edit_commands.h"
#include "editor/edit/coarse_mips_fill.h"
#include "editor/edit/material_mips_fill.h"
#include "editor/world/world.h"
#include "io/file_kind.h"
#include "io/parse.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#ifndef OROGEN_RESOURCE_DIR
#define OROGEN_RESOURCE_DIR "resources"
#endif

static void usage(FILE *out) {
    fprintf(out, "usage: orogen [options] [WORLD_FILE]\n"
                 "  WORLD_FILE          a .world or .planet parameter file to open (default: the\n"
                 "                      built-in default world)\n"
                 "  --batch FILE        run the commands in FILE with no window, then exit\n"
                 "  -c 'CMD; CMD'       run these commands with no window, then exit\n"
                 "                      (--batch and -c may be repeated; they run in order)\n"
                 "  --cache-mb N        tile cache budget in MiB (default 1024)\n"
                 "  --workers N         tile loader/generator threads (default 2)\n"
                 "  --record FILE       append every command that succeeds (typed, scripted or a\n"
                 "                      UI action such as a sculpting drag; not exit) to FILE;\n"
                 "                      orogen --batch FILE replays the session\n"
                 "  --help, --version\n"
                 "Batch errors are reported as FILE:LINE: error: MESSAGE with exit status 1.\n"
                 "Type 'help' in the console or run `orogen -c help` for the command list.\n");
}

// A script file, or standard input for "-"; a FIFO or device given by name is refused
// (it would block or never end).
static char *read_file(const char *path, size_t *len, char *why, size_t why_len) {
    og_error kind;
    int from_stdin = strcmp(path, "-") == 0;
    if (!from_stdin && file_kind_check_read(path, &kind) != 0) {
        snprintf(why, why_len, "%s", kind.msg);
        return NULL;
    }
    FILE *f = from_stdin ? stdin : fopen(path, "rb");
    if (!f) {
        snprintf(why, why_len, "%s", strerror(errno));
        return NULL;
    }
    size_t cap = 1 << 16, n = 0;
    char *buf = malloc(cap);
    for (;;) {
        if (n == cap) {
            if (cap >= ((size_t)256 << 20)) {
                snprintf(why, why_len, "larger than 256 MiB");
                free(buf);
                if (!from_stdin) fclose(f);
                return NULL;
            }
            cap *= 2;
            buf = realloc(buf, cap);
        }
        size_t got = fread(buf + n, 1, cap - n, f);
        n += got;
        if (got == 0) break;
    }
    int failed = ferror(f);
    if (!from_stdin) fclose(f);
    if (failed) {
        snprintf(why, why_len, "read error (is it a folder?)");
        free(buf);
        return NULL;
    }
    *len = n;
    return buf;
}

static int file_exists(const char *path) {
    return access(path, R_OK) == 0;
}

// The resources folder: $OROGEN_RESOURCES, the installed share/orogen/resources
// beside the binary, or the source tree's. "" when none has default.world.
static void find_resource_dir(char *dir, size_t size) {
    const char *env = getenv("OROGEN_RESOURCES");
    char exe[4096];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    const char *candidates[3] = {env, NULL, OROGEN_RESOURCE_DIR};
    char installed[4200];
    if (n > 0) {
        exe[n] = 0;
        char *slash = strrchr(exe, '/');
        if (slash) *slash = 0;
        snprintf(installed, sizeof installed, "%s/../share/orogen/resources", exe);
        candidates[1] = installed;
    }
    dir[0] = 0;
    for (int i = 0; i < 3; i++) {
        char path[4300];
        if (!candidates[i]) continue;
        snprintf(path, sizeof path, "%s/default.world", candidates[i]);
        if (file_exists(path)) {
            snprintf(dir, size, "%s", candidates[i]);
            return;
        }
    }
}

// The built-in default world: the parameters shipped in resources/default.world,
// opened as a new unsaved world so nothing is ever written into resources/.
static world *open_default_world(const char *resource_dir, const world_settings *settings,
                                 og_error *err) {
    char path[4300] = "";
    if (resource_dir[0]) snprintf(path, sizeof path, "%s/default.world", resource_dir);
    world_params p;
    world_params_default(&p, WORLD_FLAT);
    if (path[0]) {
        int errors = 0;
        og_error load_err = {{0}};
        if (world_params_load(path, &p, &errors, NULL, NULL, &load_err) != 0 || errors)
            fprintf(stderr, "orogen: warning: %s has problems; using built-in defaults\n", path);
        if (errors) world_params_default(&p, WORLD_FLAT);
    } else {
        fprintf(stderr, "orogen: warning: resources/default.world not found; using built-in "
                        "defaults\n");
    }
    p.tiles[0] = 0;
    return world_create(&p, settings, err);
}

typedef struct script {
    const char *text; // for -c
    const char *path; // for --batch
} script;

// Runs the --batch files and -c texts in order; 1 at the first that fails.
// Scripts from files or -c are the record of their edits; standard input may be a
// person typing, whose never-saved world keeps its journal like the window's.
static int scripts_are_records(const script *scripts, int script_count) {
    for (int s = 0; s < script_count; s++)
        if (scripts[s].path && !strcmp(scripts[s].path, "-")) return 0;
    return script_count > 0;
}

static int run_scripts(cmd_context *ctx, const script *scripts, int script_count, og_error *err) {
    for (int s = 0; s < script_count && !ctx->exit_requested; s++) {
        size_t len;
        char why[1100];
        char *text = NULL;
        const char *label = "-c";
        if (scripts[s].path) {
            label = scripts[s].path;
            text = read_file(scripts[s].path, &len, why, sizeof why);
            if (!text) {
                fprintf(stderr, "orogen: cannot read batch file %s: %s\n", scripts[s].path, why);
                return 1;
            }
        } else {
            len = strlen(scripts[s].text);
        }
        int rc = cmd_run(ctx, text ? text : scripts[s].text, len, label, err);
        free(text);
        if (rc != 0) {
            fflush(stdout);
            fprintf(stderr, "%s\n", err->msg);
            return 1;
        }
    }
    return 0;
}

// Interactive use needs a display for the editor window: 1 (said so) when there is none,
// instead of failing later.
static int no_display(void) {
    const char *x = getenv("DISPLAY"), *wl = getenv("WAYLAND_DISPLAY");
    if ((x && *x) || (wl && *wl)) return 0;
    fprintf(stderr, "orogen: no display found (DISPLAY and WAYLAND_DISPLAY are unset), so the "
                    "editor cannot open.\n"
                    "Batch mode needs no display: orogen --batch SCRIPT or orogen -c 'CMD; CMD'\n"
                    "  e.g. orogen -c 'info; sample 100 200; save my.world'\n");
    return 1;
}

// --record FILE: appended to; a FIFO (it would block), device or socket is refused.
static FILE *open_recording(const char *path) {
    og_error err;
    if (file_kind_check_replace(path, &err) != 0) {
        fprintf(stderr, "orogen: --record: %s\n", err.msg);
        return NULL;
    }
    FILE *f = fopen(path, "a");
    if (!f) fprintf(stderr, "orogen: --record: cannot open %s: %s\n", path, strerror(errno));
    return f;
}

int main(int argc, char **argv) {
    script scripts[64];
    int script_count = 0;
    const char *world_file = NULL, *record_path = NULL;
    world_settings settings = {0};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        int has_value = i + 1 < argc;
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            usage(stdout);
            return 0;
        } else if (strcmp(a, "--version") == 0) {
            printf("orogen 0.1\n");
            return 0;
        } else if ((strcmp(a, "--batch") == 0 || strcmp(a, "-c") == 0) && has_value) {
            if (script_count == 64) {
                fprintf(stderr, "orogen: at most 64 --batch/-c options\n");
                return 2;
            }
            scripts[script_count++] =
                a[1] == 'c' ? (script){argv[++i], NULL} : (script){NULL, argv[++i]};
        } else if (strcmp(a, "--record") == 0 && has_value) {
            record_path = argv[++i];
        } else if ((strcmp(a, "--cache-mb") == 0 || strcmp(a, "--workers") == 0) && has_value) {
            int64_t v = 0;
            long max = a[2] == 'c' ? 1L << 20 : 64;
            if (parse_i64(argv[++i], &v) != 0 || v < 1 || v > max) {
                fprintf(stderr, "orogen: %s expects an integer from 1 to %ld, got '%s'\n", a, max,
                        argv[i]);
                return 2;
            }
            if (a[2] == 'c')
                settings.cache_budget_bytes = (size_t)v << 20;
            else
                settings.workers = (int)v;
        } else if (a[0] == '-' && a[1]) {
            fprintf(stderr, "orogen: unknown or incomplete option '%s'\n", a);
            usage(stderr);
            return 2;
        } else if (!world_file) {
            world_file = a;
        } else {
            fprintf(stderr, "orogen: only one world file may be given ('%s' and '%s')\n",
                    world_file, a);
            return 2;
        }
    }
    if (script_count == 0 && no_display()) return 2;

    og_error err = {{0}};
    if (view_commands_register(&err) != 0 || window_commands_register(&err) != 0 ||
        ui_messages_register(&err) != 0) {
        fprintf(stderr, "orogen: %s\n", err.msg);
        return 1;
    }
    settings.scripted = scripts_are_records(scripts, script_count);
    FILE *recording = NULL;
    if (record_path && !(recording = open_recording(record_path))) return 1;
    // One change-notification hub for every world this run opens, so the window and
    // the viewport keep their subscriptions across new and load.
    settings.events = world_events_create();
    if (!settings.events) {
        fprintf(stderr, "orogen: out of memory\n");
        return 1;
    }
    char resource_dir[4096];
    find_resource_dir(resource_dir, sizeof resource_dir);
    // The window shows what the worlds warn about (from the first file's load on).
    if (script_count == 0) world_warnings_install(&settings);
    world *w;
    int load_errors = 0;
    if (world_file) {
        w = world_load(world_file, &settings, &load_errors, &err);
        if (w) material_mips_fill_missing(w); // paint saved before it had far levels
        if (w) coarse_mips_fill_missing(w);   // heights too
    } else {
        w = open_default_world(resource_dir, &settings, &err);
    }
    if (!w) {
        fprintf(stderr, "orogen: %s\n", err.msg);
        world_events_release(settings.events);
        if (recording) fclose(recording);
        return 1;
    }
    cmd_context ctx;
    cmd_context_init(&ctx, w, &settings, stdout, resource_dir);
    ctx.record = recording;
    ctx.reported_errors = load_errors;
    // A script's world made from a raster imports its parts as they are needed (a shard
    // of a tiled export only its own); the window shows the whole world at once.
    ctx.defer_base = script_count > 0;

    int status = script_count > 0 ? run_scripts(&ctx, scripts, script_count, &err) : 0;
    if (script_count == 0 && window_run(&ctx, &err) != 0) {
        fprintf(stderr,
                "orogen: %s\nBatch mode needs no window: orogen --batch SCRIPT or "
                "orogen -c 'CMD; CMD'\n",
                err.msg);
        status = 1;
    }
    // A script that left a stroke open: it is one undo step like any other.
    if (cmd_end_stroke(&ctx, &err) != 0) {
        fprintf(stderr, "orogen: %s\n", err.msg);
        status = 1;
    }
    // Errors that did not stop the script (a parameter file with bad lines) still fail it.
    if (script_count > 0 && ctx.reported_errors > 0 && status == 0) {
        fprintf(stderr, "orogen: %d error%s reported above; exit status 1\n", ctx.reported_errors,
                ctx.reported_errors == 1 ? "" : "s");
        status = 1;
    }
    fflush(stdout);
    if (status != 0) world_keep_journal(ctx.world);
    viewport_destroy(ctx.view_state);
    cmd_base_drop(&ctx);
    world_close(ctx.world);
    world_events_release(settings.events);
    if (recording) fclose(recording);
    return status;
}
