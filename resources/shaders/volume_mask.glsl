// Where the volume meshes replace the heightfield (renderer/volume_renderer.c): a window
// of 128 x 128 brick columns around the camera, each texel the lowest brick level it
// holds (r) and a bit per level above it (g). A brick's mesh reaches a voxel past its own
// voxels (renderer/volume_mesh.c), so hiding the ground over exactly its voxels leaves
// no gap at its edges; a surface exactly on a brick's floor belongs to the one below.
uniform isampler2D u_vol_mask;
uniform vec3 u_vol_cam;    // the camera in voxels: x, z from the window's corner; y from 0
uniform float u_vol_voxel; // metres
uniform int u_vol_on;

bool replaced_by_volume(vec3 rel) {
    if (u_vol_on == 0) return false;
    vec3 q = u_vol_cam + rel / u_vol_voxel - vec3(0.0, 1e-3, 0.0);
    ivec2 col = ivec2(floor(q.xz / 32.0));
    if (any(lessThan(col, ivec2(0))) || any(greaterThanEqual(col, ivec2(128)))) return false;
    ivec2 m = texelFetch(u_vol_mask, col, 0).rg;
    int level = int(floor(q.y / 64.0)) - m.r;
    return level >= 0 && level < 32 && ((m.g >> level) & 1) != 0;
}
