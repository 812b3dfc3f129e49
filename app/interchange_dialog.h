// The options dialogs of File > Import heightmap, Export heightmap, Export mesh and
// Export planet: after the file browser chose the file, where and how to import it
// (placement, layer, height mapping, blending), what to export (region, tiles, engine
// preset, 16-bit TIFF; a mesh's format and simplification), or a planet's mesh (seed 004's `export
// N FILE`: the cube's subdivision, the face images' size). The Layers panel's Export... opens it on
// one edit layer: the file and its format typed here, and what of the stack to write (layers=NAME,
// upto=NAME or the composite). The dialog only builds the import / export command; the editor
// checks it (app/export_check.h: a refusal is shown in the dialog) and runs it.
#ifndef OROGEN_APP_INTERCHANGE_DIALOG_H
#define OROGEN_APP_INTERCHANGE_DIALOG_H

#include "app/mesh_export_fields.h"
#include "editor/interchange/import.h"
#include "ui/ui.h"

#include <stddef.h>

typedef struct interchange_dialog {
    int open;
    int exporting; // 0: import options, 1: export options
    char path[4096];
    // import
    char x[32], z[32]; // metres: where row 0, column 0 (or the centre) goes
    int centre;        // anchor=centre
    int layer;         // 0 coarse, 1 detail
    int map_heights;   // give min= / max= (8/16-bit files)
    char min[32], max[32];
    int blend;            // replace add max min
    int resample;         // nearest bilinear bicubic
    double falloff;       // metres
    char spacing[32];     // metres between the file's samples; "": the file's own, or the world's
    double world_spacing; // the world's coarse spacing (set by the caller; 0: not shown)
    // What the file holds, read when the dialog opens: shown with the heights the
    // mapping gives them, updated as the fields change.
    int preview_ok;
    import_preview preview;
    char preview_error[1024];
    double max_height; // the world's: what 8/16-bit files map to without min/max
    // export
    int whole;          // the whole bounded world (else region)
    char region[4][32]; // X0 Z0 X1 Z1 metres
    int preset;         // none unreal unity godot houdini blender
    int bits16;         // .tif as 16-bit
    char tiles[16];     // heightmaps: "CxR" files sharing their edges ("": one file)
    // export of a mesh or volume (File > Export mesh...)
    int mesh;
    mesh_export_choices mesh_choices;
    // export of a planet (set after interchange_dialog_show)
    int planet;
    char subdivision[16]; // N: 12 x 2^N triangles
    char image_size[16];  // face images' pixels per side ("": the face grid's own)
    // export of one edit layer (set after interchange_dialog_show; "": none)
    char layer_name[64];
    int layer_what;   // 0 its change (layers=NAME), 1 the composite up to it, 2 the composite
    char error[1024]; // why the last Export was refused ("": none)
} interchange_dialog;

// Opens the dialog for path with defaults: bounded (world size in metres, 0 when
// unbounded) sets the export region to the whole world; x, z is where the view looks.
// Importing, it reads the file once for the preview (max_height: the world's).
void interchange_dialog_show(interchange_dialog *d, int exporting, const char *path,
                             double bounded_metres, double max_height, double x, double z);
// The most rows of widgets it shows (to size its rectangle).
int interchange_dialog_rows(const interchange_dialog *d);
// Draws it over r; returns 1 when the user pressed Import / Export, with the
// command in cmd (the dialog closes).
int interchange_dialog_draw(interchange_dialog *d, ui_context *ui, ui_rect r, char *cmd,
                            size_t cmd_len);

#endif
