// OpenVDB behind a C interface, built as liborogen_vdb.so and opened on first use
// (io/vdb_file.c): OpenVDB pulls in TBB, Blosc, Boost and Imath, which an editor
// session that never writes a .vdb should not load.
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetUtil.h>
#include <openvdb/tools/Prune.h>

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <cstring>
#include <exception>
#include <mutex>
#include <new>
#include <vector>

#define OROGEN_EXPORT extern "C"

namespace {

struct level_set {
    openvdb::FloatGrid::Ptr grid;
    openvdb::FloatGrid::Accessor acc;
    float background;
    explicit level_set(openvdb::FloatGrid::Ptr g, float bg)
        : grid(g), acc(g->getAccessor()), background(bg) {}
};

void say(char *why, size_t len, const char *what) {
    if (why && len) std::snprintf(why, len, "%s", what);
}

std::once_flag init_once;

} // namespace

// A narrow-band level set of voxel metres per voxel, inactive voxels at +-background.
OROGEN_EXPORT void *orogen_vdb_module_create(double voxel, float background, char *why,
                                             size_t why_len) {
    try {
        std::call_once(init_once, [] { openvdb::initialize(); });
        openvdb::FloatGrid::Ptr g = openvdb::FloatGrid::create(background);
        g->setTransform(openvdb::math::Transform::createLinearTransform(voxel));
        g->setGridClass(openvdb::GRID_LEVEL_SET);
        g->setName("surface");
        return new level_set(g, background);
    } catch (const std::exception &e) {
        say(why, why_len, e.what());
    } catch (...) {
        say(why, why_len, "OpenVDB failed creating a grid");
    }
    return nullptr;
}

// Voxels (i, j0 .. j0 + n - 1, k) take values; those at or beyond the background stay
// inactive (orogen_vdb_module_sign gives them their sign), and with overwrite an active voxel
// there is switched off.
OROGEN_EXPORT int orogen_vdb_module_set_column(void *handle, int i, int k, int j0, int n,
                                               const float *values, int overwrite) {
    level_set *ls = static_cast<level_set *>(handle);
    try {
        openvdb::Coord c(i, j0, k);
        for (int j = 0; j < n; j++) {
            float v = values[j];
            c[1] = j0 + j;
            if (std::fabs(v) < ls->background)
                ls->acc.setValue(c, v);
            else if (overwrite && ls->acc.isValueOn(c))
                ls->acc.setValueOff(c, v < 0 ? -ls->background : ls->background);
        }
        return 0;
    } catch (...) {
        return -1;
    }
}

// Moves src's voxels into dst (grids built by different threads over disjoint columns).
OROGEN_EXPORT int orogen_vdb_module_merge(void *dst, void *src) {
    try {
        level_set *d = static_cast<level_set *>(dst), *s = static_cast<level_set *>(src);
        d->acc.clear();
        s->acc.clear();
        d->grid->tree().merge(s->grid->tree());
        return 0;
    } catch (...) {
        return -1;
    }
}

OROGEN_EXPORT long long orogen_vdb_module_active_voxels(void *handle) {
    return (long long)static_cast<level_set *>(handle)->grid->activeVoxelCount();
}

// Inactive interior over the inclusive index box: -background, as tiles where the box
// covers whole nodes (the caller keeps the box clear of the voxels it set).
OROGEN_EXPORT int orogen_vdb_module_fill_inside(void *handle, const int box[6]) {
    level_set *ls = static_cast<level_set *>(handle);
    try {
        ls->acc.clear();
        ls->grid->tree().fill(openvdb::CoordBBox(openvdb::Coord(box[0], box[1], box[2]),
                                                 openvdb::Coord(box[3], box[4], box[5])),
                              -ls->background, false);
        return 0;
    } catch (...) {
        return -1;
    }
}

namespace {

// inside() over box b, or 2 when b may hold both signs: it crosses the solid's box, or
// its corners and centre disagree (where b lies within the solid's box and holds no band
// voxel, the ground cannot cross it, so those nine tell).
int box_sign(const openvdb::CoordBBox &b, const openvdb::CoordBBox &solid,
             int (*inside)(void *, int, int, int), void *user) {
    if (!b.hasOverlap(solid)) return 0;
    if (!solid.isInside(b)) return 2;
    const openvdb::Coord lo = b.min(), hi = b.max();
    int in = inside(user, (lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2);
    for (int c = 0; c < 8 && in >= 0; c++) {
        int at = inside(user, c & 1 ? hi[0] : lo[0], c & 2 ? hi[1] : lo[1], c & 4 ? hi[2] : lo[2]);
        if (at < 0) return -1;
        if (at != in) return 2;
    }
    return in;
}

// Signs box b of an inactive +background tile, halving it where it holds both signs.
int sign_box(level_set *ls, const openvdb::CoordBBox &b, const openvdb::CoordBBox &solid,
             int (*inside)(void *, int, int, int), void *user) {
    int in = b.volume() == 1 ? inside(user, b.min()[0], b.min()[1], b.min()[2])
                             : box_sign(b, solid, inside, user);
    if (in < 0) return -1;
    if (in == 1) ls->grid->tree().fill(b, -ls->background, false);
    if (in != 2) return 0;
    const openvdb::Coord lo = b.min(), hi = b.max();
    const openvdb::Coord mid((lo[0] + hi[0]) >> 1, (lo[1] + hi[1]) >> 1, (lo[2] + hi[2]) >> 1);
    for (int c = 0; c < 8; c++) {
        openvdb::Coord a(c & 1 ? mid[0] + 1 : lo[0], c & 2 ? mid[1] + 1 : lo[1],
                         c & 4 ? mid[2] + 1 : lo[2]);
        openvdb::Coord z(c & 1 ? hi[0] : mid[0], c & 2 ? hi[1] : mid[1], c & 4 ? hi[2] : mid[2]);
        if (a[0] > z[0] || a[1] > z[1] || a[2] > z[2]) continue; // a side of one voxel
        if (sign_box(ls, openvdb::CoordBBox(a, z), solid, inside, user) != 0) return -1;
    }
    return 0;
}

} // namespace

// Every inactive voxel or tile not yet signed (+background) asks inside() (1 inside,
// 0 outside, -1 failed): a leaf voxel at itself; a tile outside the solid's box
// (inclusive i0 j0 k0 i1 j1 k1, where inside() can be 1) stays outside, one within it
// takes the sign its corners and centre agree on, and one crossing the box's sides (an
// 8^3 tile over the region's last columns or its floor) is halved until each part is
// one sign. OpenVDB's own signedFloodFill guesses signs along z from neighbouring
// nodes, which is wrong for an open heightfield band; here the caller's field decides.
OROGEN_EXPORT int orogen_vdb_module_sign(void *handle, const int box[6],
                                         int (*inside)(void *, int, int, int), void *user) {
    level_set *ls = static_cast<level_set *>(handle);
    try {
        ls->acc.clear();
        // Nothing over the highest band voxel is solid (the band covers the solid's top).
        const int top = std::min(box[4], ls->grid->evalActiveVoxelBoundingBox().max()[1]);
        const openvdb::CoordBBox solid(openvdb::Coord(box[0], box[1], box[2]),
                                       openvdb::Coord(box[3], top, box[5]));
        std::vector<openvdb::CoordBBox> mixed; // split after the walk: it changes the tree
        for (auto it = ls->grid->tree().beginValueOff(); it; ++it) {
            if (*it != ls->background) continue;
            openvdb::CoordBBox b;
            it.getBoundingBox(b);
            int in = b.volume() == 1 ? inside(user, b.min()[0], b.min()[1], b.min()[2])
                                     : box_sign(b, solid, inside, user);
            if (in < 0) return -1;
            if (in == 1) it.setValue(-ls->background);
            if (in == 2) mixed.push_back(b);
        }
        for (const openvdb::CoordBBox &b : mixed)
            if (sign_box(ls, b, solid, inside, user) != 0) return -1;
        return 0;
    } catch (...) {
        return -1;
    }
}

// Finishes the level set (pruning) and writes it, with the
// fog volume `density` when fog is set, to path (the caller renames it into place).
// meta: meta_count key, value pairs of file metadata.
OROGEN_EXPORT int orogen_vdb_module_write(void *handle, const char *path, int fog,
                                          const char *const *meta, int meta_count, char *why,
                                          size_t why_len) {
    level_set *ls = static_cast<level_set *>(handle);
    try {
        ls->acc.clear();
        openvdb::tools::prune(ls->grid->tree()); // mixed-sign inactive nodes stay
        openvdb::GridPtrVec grids;
        grids.push_back(ls->grid);
        openvdb::MetaMap file_meta;
        for (int m = 0; m < meta_count; m++) {
            ls->grid->insertMeta(meta[2 * m], openvdb::StringMetadata(meta[2 * m + 1]));
            file_meta.insertMeta(meta[2 * m], openvdb::StringMetadata(meta[2 * m + 1]));
        }
        if (fog) {
            openvdb::FloatGrid::Ptr density = ls->grid->deepCopy();
            openvdb::tools::sdfToFogVolume(*density);
            density->setName("density");
            grids.push_back(density);
        }
        openvdb::io::File file(path);
        file.write(grids, file_meta);
        file.close();
        return 0;
    } catch (const std::exception &e) {
        say(why, why_len, e.what());
    } catch (...) {
        say(why, why_len, "OpenVDB failed writing the file");
    }
    return -1;
}

OROGEN_EXPORT void orogen_vdb_module_free(void *handle) {
    delete static_cast<level_set *>(handle);
}
