// A planet's climate, per vertex: smooth noise over the planet-fixed direction (so it is
// continuous across faces), band-limited to what a vertex grid can carry from orbit.
// x: moisture 0..1 (continental scale, drier in the subtropics); y: breakup -1..1, the
// scale of regions (a few hundred km on Earth, down to tens), which moves borders between
// materials so none follows a contour; z: patches -1..1, finer octaves (down to a few
// hundred metres on Earth) that break the borders of snow and of the biomes into
// patches, each octave faded out where its cells would be under a few pixels
// (cell_angle: a cell's size over the vertex's distance from the camera).

uint climate_hash(uvec3 q) {
    q = q * uvec3(1597334673u, 3812015801u, 2798796415u);
    uint n = (q.x ^ q.y ^ q.z) * 1597334673u;
    return n ^ (n >> 16);
}

// Value noise in -1..1 with a smooth (quintic) blend between lattice points.
float climate_noise(vec3 p, uint seed) {
    vec3 i = floor(p), f = p - i;
    vec3 w = f * f * f * (f * (f * 6.0 - 15.0) + 10.0);
    uvec3 q = uvec3(ivec3(i) + ivec3(1 << 20));
    float v[8];
    for (int k = 0; k < 8; k++)
        v[k] = float(climate_hash(q + uvec3(k & 1, (k >> 1) & 1, (k >> 2) & 1) + seed)) /
                   2147483647.5 - 1.0;
    float x0 = mix(mix(v[0], v[1], w.x), mix(v[2], v[3], w.x), w.y);
    float x1 = mix(mix(v[4], v[5], w.x), mix(v[6], v[7], w.x), w.y);
    return mix(x0, x1, w.z);
}

float climate_octave(vec3 dir, float cells, uint seed, float dist) {
    float cell_angle = u_radius / (cells * max(dist, 1.0));
    return climate_noise(dir * cells, seed) * smoothstep(0.003, 0.012, cell_angle);
}

vec3 planet_climate(vec3 dir, float dist) {
    float lat = abs(dir.y);
    float wet = 0.5 + 0.45 * climate_noise(dir * 3.0, 11u) + 0.25 * climate_noise(dir * 7.0, 12u);
    // Deserts under the subtropical highs (about 25 degrees: sine 0.42), rain at the
    // equator and in the westerlies.
    wet += 0.25 * (1.0 - smoothstep(0.0, 0.25, lat)) - 0.35 * exp(-pow((lat - 0.42) / 0.14, 2.0));
    float breakup = 0.6 * climate_noise(dir * 40.0, 21u) + 0.4 * climate_noise(dir * 110.0, 22u);
    float patches = 0.45 * climate_octave(dir, 300.0, 31u, dist) +
                    0.3 * climate_octave(dir, 900.0, 32u, dist) +
                    0.2 * climate_octave(dir, 2700.0, 33u, dist) +
                    0.12 * climate_octave(dir, 8100.0, 34u, dist);
    return vec3(clamp(wet, 0.0, 1.0), breakup, patches);
}
