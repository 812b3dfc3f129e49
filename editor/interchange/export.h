// Export: a rectangle of the world (or the whole bounded world) written as a
// heightmap (16-bit PNG / TIFF, float GeoTIFF, float EXR, R16 RAW) with its sidecar,
// in the convention import reads back (io/raster.h, import.h): row 0, column 0 is
// the rectangle's corner nearest the origin, columns toward +X, rows toward +Z.
#ifndef OROGEN_EDITOR_INTERCHANGE_EXPORT_H
#define OROGEN_EDITOR_INTERCHANGE_EXPORT_H

#include "editor/interchange/export_mesh.h"
#include "editor/world/world.h"
#include "editor/layers/layer_table.h"
#include "io/err.h"
#include "io/tile.h"

#include <stdint.h>
#include <stdio.h>

// The most samples one export reads (per side, and in all).
#define EXPORT_MAX_SIDE 65536
#define EXPORT_MAX_SAMPLES ((int64_t)1 << 28)

typedef enum export_preset {
    EXPORT_PRESET_NONE,
    EXPORT_PRESET_UNREAL,
    EXPORT_PRESET_UNITY,
    EXPORT_PRESET_GODOT,
    EXPORT_PRESET_HOUDINI,
    EXPORT_PRESET_BLENDER
} export_preset;

typedef enum export_layers {
    EXPORT_LAYERS_COMPOSITE = 0,
    EXPORT_LAYERS_DELTA,
    EXPORT_LAYERS_UPTO
} export_layers;

typedef struct export_options {
    int has_region;
    double x0, z0, x1, z1; // metres, corners (inclusive samples)
    export_preset preset;
    int fit_crop; // fit=crop: presets unity/unreal crop to the engine's size (default resample)
    tile_layer layer;
    int bits; // .tif: 16 or 32 (default 32)
    int has_min_max, has_scale;
    double min, max;      // 16-bit: metres at stored 0 and 65535
    double scale, offset; // 16-bit: height = stored x scale + offset
    // Tiled export: tiles_x x tiles_y files sharing one sample along each seam, named
    // by pattern ({name} {x} {y}; "" = the preset's convention); this run writes the
    // tiles k (row-major) with floor(k x shard_count / tiles) == shard: its contiguous run.
    int tiles_x, tiles_y;
    char pattern[128];
    int shard, shard_count;
    // Meshes (.obj .ply .glb): metres of error allowed, a closed base, centred at 0.
    double simplify;
    int solid, centred;
    int image_layer; // layer=normals (1) or materials (2): that layer as images instead
    // layers=composite (the default), layers=NAME (one height layer's signed change: what
    // it adds to the layers below it) or layers=upto=NAME (the composite of the layers up
    // to NAME); heightmaps only.
    export_layers layers;
    char layers_name[LAYER_NAME_MAX];
    // .vdb: voxel metres (0 = the world's volume voxel), narrow band half width in
    // voxels, a density fog volume beside the level set, and how far the solid reaches
    // below the region's lowest ground (metres; < 0: 16 voxels).
    double voxel;
    int band, fog;
    double depth;
    // Heightmaps: called with the level-0 samples of a rectangle before they are read
    // (NULL: nothing to do); a world that imports its parts as needed imports them
    // (editor/cmd/base_pending.h). Not a key.
    int (*before_read)(void *user, grid_rect r, og_error *err);
    void *before_read_user;
    // The lowest and highest composite heights of level-0 samples r when known without
    // reading them (1; 0: read them), for a tiled 16-bit export's shared mapping: a world
    // made from a raster and not changed since knows them from the raster. Not a key.
    int (*height_range)(void *user, grid_rect r, double *lo, double *hi);
} export_options;

void export_options_defaults(export_options *o);
// region=X0,Z0,X1,Z1 preset= fit=crop|resample layer= bits= min= max= scale= offset= tiles=CxR
// pattern= shard=I/N simplify= solid= centred= voxel= band= fog= depth=
int export_options_set(export_options *o, const char *key, const char *value, og_error *err);
const char *export_preset_name(export_preset p);

typedef struct export_report {
    int width, height;
    double spacing, origin_x, origin_z;
    double spacing_z;     // metres between rows (a preset's resampling may differ from spacing)
    double min, max;      // metres
    double scale, offset; // the stored mapping (1, 0 for float files)
    long long bytes;      // written (file + sidecar)
    char format[16];
    char changed[512];              // what a preset or the tiling changed ("" if nothing)
    int tiles_written, tiles_total; // tiled export: by this run, in the set
    int tile_width, tile_height;
} export_report;

// Writes path (format from its extension) and path.json; tiled, the tiles (each with
// its own sidecar) and path.json describing the set (written by shard 0). Prints what to type into
// the target engine to hints (may be NULL). Nothing is written on failure; an
// existing file stays as it was.
int export_heightmap(world *w, const char *path, const export_options *o, FILE *hints,
                     export_report *report, og_error *err);

// layer=normals / materials (export_layers.h): the files written, one per line.
int export_layer_file(world *w, const char *path, const export_options *o, char *files,
                      size_t files_len, og_error *err);

// A mesh of the region (export_mesh.h) for .obj, .ply and .glb paths.
int export_mesh_file(world *w, const char *path, const export_options *o, export_mesh_report *rep,
                     og_error *err);

#endif
