#include "app/file_browser.h"

#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

// The files a mode lists besides folders (the extension filter).
static int listed_file(file_browser_mode mode, const char *name) {
    const char *dot = strrchr(name, '.');
    if (!dot) return 0;
    if (mode == FILE_BROWSER_SCRIPT) return strcmp(dot, ".og") == 0 || strcmp(dot, ".txt") == 0;
    if (mode == FILE_BROWSER_EXPORT_PLANET) return strcasecmp(dot, ".obj") == 0;
    if (mode == FILE_BROWSER_EXPORT_MESH)
        return !strcasecmp(dot, ".glb") || !strcasecmp(dot, ".obj") || !strcasecmp(dot, ".ply") ||
               !strcasecmp(dot, ".vdb");
    if (mode == FILE_BROWSER_NEW_FROM) mode = FILE_BROWSER_IMPORT; // the same files
    if (mode == FILE_BROWSER_IMPORT || mode == FILE_BROWSER_EXPORT) {
        static const char *const rasters[] = {".png", ".tif", ".tiff", ".exr", ".r16", ".raw",
                                              ".hgt", ".asc", ".pgm",  ".pfm", ".dem", ".bil"};
        static const char *const exports[] = {".png", ".tif", ".tiff", ".exr", ".r16", ".raw"};
        const char *const *list = mode == FILE_BROWSER_IMPORT ? rasters : exports;
        int n = mode == FILE_BROWSER_IMPORT ? 12 : 6;
        for (int i = 0; i < n; i++)
            if (strcasecmp(dot, list[i]) == 0) return 1;
        return 0;
    }
    return strcmp(dot, ".world") == 0 || strcmp(dot, ".planet") == 0;
}

static const char *const titles[] = {"Open",
                                     "Save as",
                                     "Save session script",
                                     "Import heightmap",
                                     "Export heightmap",
                                     "Export planet",
                                     "New world from heightmap",
                                     "Export mesh"};
static const char *const intros[] = {
    "Open a world (.world or .planet)",
    "Save the world as (a .world or .planet file; its tiles go beside it as NAME.tiles)",
    "Save this session's commands as a script (.og) that replays it on the starting world",
    "Import a heightmap: PNG, TIFF, EXR, RAW/R16, SRTM .hgt, GeoTIFF, ASCII grid",
    "Export a heightmap: .png (16-bit), .tif (float GeoTIFF), .exr (float), .r16",
    "Export the planet: an .obj and its face height and normal maps",
    "A new flat world of a heightmap's extent and spacing (PNG, TIFF, EXR, RAW, .hgt, ...)",
    "Export a mesh (.glb, .obj, .ply) or a volume (.vdb)"};

static int sort_mode; // qsort has no user pointer

static int compare(const void *pa, const void *pb) {
    const file_browser_entry *a = pa, *b = pb;
    if (a->is_dir != b->is_dir) return b->is_dir - a->is_dir; // folders first
    if (sort_mode == 1 && a->mtime != b->mtime) return a->mtime > b->mtime ? -1 : 1;
    if (sort_mode == 2 && a->size != b->size) return a->size > b->size ? -1 : 1;
    return strcmp(a->name, b->name);
}

void file_browser_refresh(file_browser *b) {
    b->count = 0;
    b->error[0] = 0;
    DIR *d = opendir(b->dir);
    if (!d) {
        snprintf(b->error, sizeof b->error, "%.400s: %s", b->dir, strerror(errno));
        return;
    }
    struct dirent *de;
    while ((de = readdir(d)) && b->count < FILE_BROWSER_MAX) {
        if (de->d_name[0] == '.') continue; // hidden files and . ..
        char full[8192];
        snprintf(full, sizeof full, "%s/%s", b->dir, de->d_name);
        struct stat st;
        if (stat(full, &st) != 0) continue;
        int is_dir = S_ISDIR(st.st_mode);
        if (!is_dir && !listed_file(b->mode, de->d_name)) continue;
        file_browser_entry *e = &b->entries[b->count++];
        snprintf(e->name, sizeof e->name, "%s", de->d_name);
        e->is_dir = is_dir;
        e->size = (long long)st.st_size;
        e->mtime = st.st_mtime;
    }
    closedir(d);
    sort_mode = b->sort;
    qsort(b->entries, (size_t)b->count, sizeof b->entries[0], compare);
}

void file_browser_show(file_browser *b, file_browser_mode mode, const char *start) {
    b->open = 1;
    b->mode = mode;
    b->confirm_overwrite = 0;
    snprintf(b->path, sizeof b->path, "%s", start ? start : "");
    char dir[4096];
    if (start && *start) {
        snprintf(dir, sizeof dir, "%s", start);
        char *slash = strrchr(dir, '/');
        if (slash)
            *slash = 0;
        else if (!getcwd(dir, sizeof dir))
            snprintf(dir, sizeof dir, ".");
        if (!dir[0]) snprintf(dir, sizeof dir, "/");
    } else if (!getcwd(dir, sizeof dir)) {
        snprintf(dir, sizeof dir, ".");
    }
    snprintf(b->dir, sizeof b->dir, "%.4095s", dir);
    file_browser_refresh(b);
}

static void go_to(file_browser *b, const char *dir) {
    snprintf(b->dir, sizeof b->dir, "%.4095s", dir);
    file_browser_refresh(b);
}

int file_browser_draw(file_browser *b, ui_context *ui, ui_rect r) {
    const ui_theme *t = ui_get_theme(ui);
    int chosen = 0;
    ui_panel_begin(ui, titles[b->mode], r);
    float line = ui_em(ui, 1.4f);
    ui_label_wrapped(ui, intros[b->mode], t->text); // never cut at a narrow dialog's edge
    float top[4] = {-0.2f, -0.2f, -0.3f, 0};
    ui_row(ui, 4, top, line);
    if (ui_button(ui, "Parent")) {
        char dir[4096];
        snprintf(dir, sizeof dir, "%s", b->dir);
        char *slash = strrchr(dir, '/');
        if (slash && slash != dir)
            *slash = 0;
        else
            snprintf(dir, sizeof dir, "/");
        go_to(b, dir);
    }
    ui_tooltip(ui, "The folder above this one");
    if (ui_button(ui, "Home")) {
        const char *home = getenv("HOME");
        go_to(b, home && *home ? home : "/");
    }
    ui_tooltip(ui, "Your home folder");
    static const char *const sorts[] = {"name", "date", "size"};
    if (ui_combo(ui, "Sort", &b->sort, sorts, 3)) file_browser_refresh(b);
    ui_tooltip(ui, "Order of the files (folders come first)");
    char where[4200];
    snprintf(where, sizeof where, "%s", b->dir);
    ui_label_colored(ui, where, t->text_dim);
    ui_tooltip(ui, "The folder shown");
    // The list: folders open on a click, files fill the path field.
    ui_row(ui, 1, NULL, line);
    ui_rect list = ui_next_cell(ui);
    float list_h = r.y + r.h - list.y - 3.0f * line; // the rest, less the path and buttons
    list.h = list_h > line ? list_h : line;
    ui_panel_begin(ui, "Files", list);
    ui_row(ui, 1, NULL, ui_em(ui, 1.2f));
    if (b->error[0]) {
        ui_label_wrapped(ui, b->error, t->text_error);
        ui_row(ui, 1, NULL, ui_em(ui, 1.2f));
    }
    for (int i = 0; i < b->count; i++) {
        file_browser_entry *e = &b->entries[i];
        char label[400];
        if (e->is_dir)
            snprintf(label, sizeof label, "%s/##%d", e->name, i);
        else
            snprintf(label, sizeof label, "%s   (%lld KiB)##%d", e->name, e->size / 1024, i);
        char full[8192];
        snprintf(full, sizeof full, "%s/%s", strcmp(b->dir, "/") == 0 ? "" : b->dir, e->name);
        if (ui_selectable(ui, label, strcmp(full, b->path) == 0)) {
            if (e->is_dir) {
                go_to(b, full);
                break;
            }
            snprintf(b->path, sizeof b->path, "%.4095s", full);
            b->confirm_overwrite = 0;
        }
        ui_tooltip(ui, e->is_dir ? "Open this folder" : "Choose this file");
    }
    ui_panel_end(ui);
    // Leave room for the list in this panel's layout.
    ui_row(ui, 1, NULL, list.h - line);
    ui_next_cell(ui);
    ui_row(ui, 1, NULL, line);
    int rc = ui_textbox_flags(ui, "Path", b->path, sizeof b->path, UI_TEXTBOX_SELECT_ALL);
    ui_tooltip(ui, "The file: type a path, or pick one above");
    float bottom[2] = {-0.5f, 0};
    ui_row(ui, 2, bottom, line);
    static const char *const go_labels[] = {"Open##go", "Save##go", "Save##go",   "Next##go",
                                            "Next##go", "Next##go", "Create##go", "Next##go"};
    static const char *const go_tips[] = {"Open the chosen world",
                                          "Save the world there",
                                          "Write the script there",
                                          "Choose how to import it (next: the import options)",
                                          "Choose what to export there (next: the export options)",
                                          "Export the planet there (next: its subdivision)",
                                          "Make a new world of it (asks first about unsaved "
                                          "changes)",
                                          "Choose what to export there (next: the mesh options)"};
    int go = ui_button(ui, b->confirm_overwrite ? "Overwrite##go" : go_labels[b->mode]) ||
             (rc & UI_TEXT_SUBMIT);
    ui_tooltip(ui, go_tips[b->mode]);
    if (ui_button(ui, "Cancel")) b->open = 0;
    ui_tooltip(ui, "Close without choosing (Esc)");
    ui_panel_end(ui);
    if (go && b->path[0]) {
        struct stat st;
        int exists = stat(b->path, &st) == 0;
        int opening = b->mode == FILE_BROWSER_OPEN || b->mode == FILE_BROWSER_IMPORT ||
                      b->mode == FILE_BROWSER_NEW_FROM;
        if (opening && !exists) {
            snprintf(b->error, sizeof b->error, "%.400s: no such file", b->path);
        } else if (exists && S_ISDIR(st.st_mode)) {
            go_to(b, b->path);
        } else if (!opening && exists && !b->confirm_overwrite) {
            b->confirm_overwrite = 1; // the button asks again: Overwrite
            snprintf(b->error, sizeof b->error, "%.400s exists: press Overwrite to replace it",
                     b->path);
        } else {
            chosen = 1;
            b->open = 0;
        }
    }
    return chosen;
}
