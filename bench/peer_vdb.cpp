// The .vdb export benchmark's peer: OpenVDB's own tools::meshToLevelSet building the
// narrow-band level set of a heightfield's triangle mesh (two triangles per cell),
// behind a C interface for bench_volume.c.
#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>

#include <chrono>
#include <vector>

// heights: n x n samples `spacing` metres apart from (x0, z0); voxel and half width
// (voxels) as the export's. Returns the seconds meshToLevelSet took; *active gets the
// level set's active voxel count.
extern "C" double peer_vdb_mesh_to_level_set(const float *heights, int n, double spacing, double x0,
                                             double z0, double voxel, int half_width,
                                             long long *active) {
    openvdb::initialize();
    std::vector<openvdb::Vec3s> points((size_t)n * (size_t)n);
    for (int z = 0; z < n; z++)
        for (int x = 0; x < n; x++)
            points[(size_t)z * n + x] = openvdb::Vec3s(
                (float)(x0 + x * spacing), heights[(size_t)z * n + x], (float)(z0 + z * spacing));
    std::vector<openvdb::Vec3I> triangles;
    triangles.reserve((size_t)(n - 1) * (n - 1) * 2);
    for (int z = 0; z + 1 < n; z++)
        for (int x = 0; x + 1 < n; x++) {
            unsigned a = (unsigned)(z * n + x), b = a + 1, c = a + (unsigned)n, d = c + 1;
            triangles.emplace_back(a, c, b);
            triangles.emplace_back(b, c, d);
        }
    openvdb::math::Transform::Ptr xform = openvdb::math::Transform::createLinearTransform(voxel);
    auto t0 = std::chrono::steady_clock::now();
    openvdb::FloatGrid::Ptr grid = openvdb::tools::meshToLevelSet<openvdb::FloatGrid>(
        *xform, points, triangles, (float)half_width);
    auto t1 = std::chrono::steady_clock::now();
    *active = (long long)grid->activeVoxelCount();
    return std::chrono::duration<double>(t1 - t0).count();
}
