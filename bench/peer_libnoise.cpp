// The fBm benchmark's peer: libnoise's Perlin module (8 octaves, persistence 0.5,
// lacunarity 2, QUALITY_STD), behind a C interface for bench_fbm.c.
#include <libnoise/noise.h>

#include <cstddef>

static noise::module::Perlin make_perlin() {
    noise::module::Perlin p;
    p.SetOctaveCount(8);
    p.SetFrequency(1.0);
    p.SetPersistence(0.5);
    p.SetLacunarity(2.0);
    p.SetNoiseQuality(noise::QUALITY_STD);
    p.SetSeed(1);
    return p;
}

// out[j * nx + i] = Perlin(xs[i], ys[j], z): libnoise is 3D only, so a flat grid
// is a slice at constant z.
extern "C" void peer_libnoise_grid(const double *xs, int nx, const double *ys, int ny, double z,
                                   float *out) {
    noise::module::Perlin p = make_perlin();
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++)
            out[(size_t)j * (size_t)nx + (size_t)i] = (float)p.GetValue(xs[i], ys[j], z);
}

// out[i] = Perlin(xyz[3i], xyz[3i+1], xyz[3i+2]).
extern "C" void peer_libnoise_points(const double *xyz, size_t n, float *out) {
    noise::module::Perlin p = make_perlin();
    for (size_t i = 0; i < n; i++)
        out[i] = (float)p.GetValue(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
}
