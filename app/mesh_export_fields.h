// The choices of File > Export mesh... (after the file browser chose the file): the
// format (the file's extension), and for a surface mesh (.glb .obj .ply) how far it may
// be simplified, a closed solid, centred at the origin; for a .vdb volume the voxel size
// and a fog volume instead of a level set. The region is the export dialog's own.
#ifndef OROGEN_APP_MESH_EXPORT_FIELDS_H
#define OROGEN_APP_MESH_EXPORT_FIELDS_H

#include "app/interchange_dialog.h"

#include <stddef.h>

// Draws the fields into the export dialog's panel.
void mesh_export_fields(interchange_dialog *d, ui_context *ui);
// The export command's options for those choices (" simplify=2 centred=1"; "" for none).
void mesh_export_options(const interchange_dialog *d, char *out, size_t len);
// 1 when d's file is a volume (.vdb), 0 for a surface mesh.
int mesh_export_is_volume(const interchange_dialog *d);

#endif
