// The choices of File > Export mesh... (after the file browser chose the file): the
// format (the file's extension), and for a surface mesh (.glb .obj .ply) how far it may
// be simplified, a closed solid, centred at the origin; for a .vdb volume the voxel size
// and a fog volume instead of a level set. The export dialog (interchange_dialog.h) holds
// them beside the region.
#ifndef OROGEN_APP_MESH_EXPORT_FIELDS_H
#define OROGEN_APP_MESH_EXPORT_FIELDS_H

#include "ui/ui.h"

#include <stddef.h>

typedef struct mesh_export_choices {
    char simplify[32]; // metres ("": every sample)
    int solid, centred;
    char voxel[32]; // .vdb: metres ("": the world's spacing)
    int fog;        // .vdb: a fog volume, not a level set
} mesh_export_choices;

// Draws the fields into the export dialog's panel; choosing a format renames path's
// extension (path holds path_size bytes).
void mesh_export_fields(mesh_export_choices *m, char *path, size_t path_size, ui_context *ui);
// The export command's options for m and path's format (" simplify=2 centred=1"; "").
void mesh_export_options(const mesh_export_choices *m, const char *path, char *out, size_t len);
// 1 when path names a volume (.vdb), 0 otherwise.
int mesh_export_is_volume(const char *path);
// 1 when path's extension is one this export writes (.glb .obj .ply .vdb).
int mesh_export_known(const char *path);

#endif
