// OpenVDB level sets (.vdb): the solid of a region as a narrow-band signed distance
// field that Houdini, Blender and game pipelines read. Built column by column (one
// builder per thread, merged), its inactive space signed by the caller, then written atomically.
// OpenVDB itself lives in the module liborogen_vdb.so (io/modules/vdb_module.cpp), opened on first
// use.
#ifndef OROGEN_IO_VDB_FILE_H
#define OROGEN_IO_VDB_FILE_H

#include "io/err.h"

#include <stddef.h>
#include <stdint.h>

typedef struct vdb_level_set vdb_level_set;

// A FloatGrid level set named "surface": voxel metres per voxel, index (i, j, k) at
// world (i, j, k) x voxel (y up), inactive voxels at +-background metres.
vdb_level_set *vdb_level_set_create(double voxel, float background, og_error *err);
// Sets voxels (i, j, k) for j in [j0, j0 + n) (metres, negative inside); values at or
// beyond the background stay inactive (with overwrite, a voxel set before is switched off).
int vdb_level_set_column(vdb_level_set *ls, int32_t i, int32_t k, int32_t j0, int32_t n,
                         const float *values, int overwrite, og_error *err);
// Moves src's voxels into dst (disjoint columns; src is left empty).
int vdb_level_set_merge(vdb_level_set *dst, vdb_level_set *src, og_error *err);
// Inactive interior (-background) over the inclusive index box i0, j0, k0, i1, j1, k1,
// as whole tiles where it can; the box must hold no voxel set before.
int vdb_level_set_fill_inside(vdb_level_set *ls, const int32_t box[6], og_error *err);
// Gives every inactive value still at +background the sign inside() says (1 inside,
// 0 outside, -1 failed); inside() is 0 outside the inclusive index box i0, j0, k0, i1,
// j1, k1. A tile crossing the box's sides is split until each part has one sign.
int vdb_level_set_sign(vdb_level_set *ls, const int32_t box[6],
                       int (*inside)(void *user, int i, int j, int k), void *user, og_error *err);
long long vdb_level_set_active_voxels(vdb_level_set *ls);
// Prunes and writes path atomically (temp file
// beside it, fsync, rename) with meta_count key/value pairs of metadata (meta[2m],
// meta[2m + 1]); with fog, also a "density" fog volume made from the level set.
int vdb_level_set_write(vdb_level_set *ls, const char *path, int fog, const char *const *meta,
                        int meta_count, og_error *err);
void vdb_level_set_free(vdb_level_set *ls);

#endif
