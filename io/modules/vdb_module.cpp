// OpenVDB behind a C interface, built as liborogen_vdb.so and opened on first use
// (io/vdb_file.c): OpenVDB pulls in TBB, Blosc, Boost and Imath, which an editor
// session that never writes a .vdb should not load.
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetUtil.h>
#include <openvdb/tools/Prune.h>

#include <cstdio>
#include <cmath>
#include <cstring>
#include <exception>
#include <mutex>
#include <new>

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

// Every inactive voxel or tile not yet signed (+background) asks inside() at its voxel
// (a tile at its centre when its corners are inside too; a tile never holds the
// surface, so that tells). OpenVDB's
// own signedFloodFill guesses signs along z from neighbouring nodes, which is wrong for
// an open heightfield band; here the caller's field decides.
OROGEN_EXPORT int orogen_vdb_module_sign(void *handle, int (*inside)(void *, int, int, int),
                                         void *user) {
    level_set *ls = static_cast<level_set *>(handle);
    try {
        ls->acc.clear();
        for (auto it = ls->grid->tree().beginValueOff(); it; ++it) {
            if (*it != ls->background) continue;
            openvdb::CoordBBox b;
            it.getBoundingBox(b);
            const openvdb::Coord lo = b.min(), hi = b.max(), n = b.dim();
            // A tile is one sign: where it reaches out of the solid's box it stays outside.
            int in = inside(user, lo[0], lo[1], lo[2]);
            if (in > 0 && n[0] > 1) in = inside(user, hi[0], hi[1], hi[2]);
            if (in > 0 && n[0] > 1)
                in = inside(user, lo[0] + n[0] / 2, lo[1] + n[1] / 2, lo[2] + n[2] / 2);
            if (in < 0) return -1;
            if (in) it.setValue(-ls->background);
        }
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
