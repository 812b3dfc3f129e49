// Seed 004's planet export, `export N FILE.obj`: the N-th subdivision of the cube
// (ROAM's bintree, 12 x 2^N triangles and 6 x 2^N + 2 vertices) lifted onto the
// planet's surface, watertight for every N (vertices on face edges and corners are
// shared by the faces that meet there), with vertex normals and per-face texture
// coordinates into six images per kind: FILE_height_F.png (16-bit grey, heights in
// metres by FILE_height_F.png.json) and FILE_normal_F.png (8-bit object-space
// normals), F = 0..5 for the cube faces +X -X +Y -Y +Z -Z. Each image pixel is one
// sample of a mip level of the face grid (the level whose side fits size=), so the
// images are the world's own box-filtered heights, edits included.
//
// Every file is written to a hidden staging name first and renamed into place only
// when all of them are complete (the OBJ last): a failure leaves no new file behind
// and every old file as it was.
#ifndef OROGEN_EDITOR_INTERCHANGE_EXPORT_PLANET_H
#define OROGEN_EDITOR_INTERCHANGE_EXPORT_PLANET_H

#include "editor/world/world.h"
#include "io/err.h"

#include <stddef.h>

#define EXPORT_PLANET_MAX_SUBDIVISION 20 // 12.6 M triangles: a ~1.5 GB OBJ
#define EXPORT_PLANET_MAX_IMAGE 8192     // pixels per side of a face image
#define EXPORT_PLANET_DEFAULT_IMAGE 1024

typedef struct export_planet_report {
    size_t vertices, triangles;
    int image_size;  // pixels per side of each face image
    int level;       // the face grid's mip level the images hold
    double min, max; // metres above the datum over the six height images
    long long bytes; // all files written
    int files;
} export_planet_report;

// 1 when argv looks like seed 004's `export N FILE` (a whole number, then a file).
int export_planet_wanted(const char *first);

// image_size: the largest face image side wanted (0: the default).
int export_planet(world *w, int subdivision, const char *path, int image_size,
                  export_planet_report *rep, og_error *err);

#endif
