// The in-app file browser (no native dialogs exist under Xvfb or on every desktop):
// a folder's sub-folders and the files of the mode's kind (worlds: .world, .planet;
// scripts: .og, .txt; heightmaps: images, rasters, RAW), parent and home, a path field, sorting by
// name, date or size, and for saving an overwrite confirmation.
#ifndef OROGEN_APP_FILE_BROWSER_H
#define OROGEN_APP_FILE_BROWSER_H

#include "ui/ui.h"

#include <stddef.h>
#include <time.h>

#define FILE_BROWSER_MAX 512

typedef enum file_browser_mode {
    FILE_BROWSER_OPEN,          // a world to open
    FILE_BROWSER_SAVE,          // where to save the world
    FILE_BROWSER_SCRIPT,        // where to save the session as a script (.og)
    FILE_BROWSER_IMPORT,        // a heightmap or elevation raster to import
    FILE_BROWSER_EXPORT,        // where to export a heightmap
    FILE_BROWSER_EXPORT_PLANET, // where to export a planet's mesh and face images (.obj)
    FILE_BROWSER_NEW_FROM,      // a heightmap to make a new world of (its extent and spacing)
    FILE_BROWSER_EXPORT_MESH,   // where to export a mesh (.glb .obj .ply) or a volume (.vdb)
} file_browser_mode;

typedef struct file_browser_entry {
    char name[256];
    int is_dir;
    long long size;
    time_t mtime;
} file_browser_entry;

typedef struct file_browser {
    int open;
    file_browser_mode mode;
    char dir[4096];
    char path[4096]; // the path field: the chosen file
    file_browser_entry entries[FILE_BROWSER_MAX];
    int count;
    int sort; // 0 name, 1 date, 2 size
    int confirm_overwrite;
    char error[512];
} file_browser;

// Opens the browser on the folder of start (or the current folder when start is empty).
void file_browser_show(file_browser *b, file_browser_mode mode, const char *start);
// Lists b->dir again.
void file_browser_refresh(file_browser *b);
// Draws the browser as a modal dialog over r; returns 1 when a file was chosen (in
// b->path; the browser closes).
int file_browser_draw(file_browser *b, ui_context *ui, ui_rect r);

#endif
