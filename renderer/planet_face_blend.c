// Where faces meet, the material textures' face-local metres jump: the faces' axes
// turn and mirror there, and the texture's pattern broke along a straight line (at a
// cube corner, three patterns met). Within a band along every edge the ground blends the
// textures of each face whose edge is near, by weights that depend on the point alone:
// a face's weight falls from 1 a band inside its edge through 1/2 on it to 0 a band past
// it (its coordinates extend past its edges), and the weights are normalised (1/3 each
// at a corner). Both sides of an edge then show the same mix, and the texture runs on.
#include "renderer/planet_internal.h"

#include "editor/params/world_grid.h"

#include <string.h>

// Metres on each side of an edge the blend spans: the far scale's period, so neither
// scale's pattern can end along a line; a face's sixteenth on small planets.
static double band_metres(double face_metres) {
    return fmin(TEX_PERIOD_FAR, face_metres / 16.0);
}

// A face's weight e metres past its edge (negative inside).
static double face_weight(double e, double band) {
    const double x = fmin(fmax((e + band) / (2.0 * band), 0.0), 1.0);
    return 1.0 - x * x * (3.0 - 2.0 * x);
}

int planet_face_blend(const planet_renderer *r, int face, const double s[], const double t[],
                      const double *pos, int ring, float *out) {
    const double face_metres = (double)r->face_samples * r->cell_arc;
    const double band = band_metres(face_metres), band_st = 2.0 * band / face_metres;
    for (int q = 0; q < GRID_VERTS; q++)
        memset(out + (size_t)q * VERTEX_FLOATS + BLEND_FLOAT0, 0, sizeof(float) * 6);
    // Far from every edge of its face, a chunk shows its face's texture alone.
    const double far = 1.0 - band_st;
    if (fabs(s[1]) < far && fabs(s[BLOCK + 1]) < far && fabs(t[1]) < far &&
        fabs(t[BLOCK + 1]) < far)
        return 0;
    // Each vertex's weight for every face.
    static double weight[GRID_VERTS][6];
    static double st[GRID_VERTS][6][2];
    static unsigned char on[GRID_VERTS][6]; // the face's coordinates extend to the vertex
    double most[6] = {0};
    for (int gj = 0; gj <= BLOCK; gj++)
        for (int gi = 0; gi <= BLOCK; gi++) {
            const int q = gj * (BLOCK + 1) + gi;
            const double *p = pos + 3 * ((size_t)(gj + 1) * ring + gi + 1);
            double sum = 0;
            for (int f = 0; f < 6; f++) {
                double fs = s[gi + 1], ft = t[gj + 1];
                weight[q][f] = 0;
                on[q][f] = f == face || world_grid_face_coords_on(f, p, &fs, &ft);
                if (!on[q][f]) continue;
                const double past = (fmax(fabs(fs), fabs(ft)) - 1.0) * 0.5 * face_metres;
                weight[q][f] = face_weight(f == face ? fmin(past, 0.0) : past, band);
                st[q][f][0] = fs, st[q][f][1] = ft;
                sum += weight[q][f];
            }
            for (int f = 0; f < 6; f++) {
                weight[q][f] /= sum;
                most[f] = fmax(most[f], weight[q][f]);
            }
        }
    // The two other faces with the most weight (a corner has two, an edge one).
    int other[2] = {-1, -1}, count = 0;
    for (int k = 0; k < 2; k++) {
        int best = -1;
        for (int f = 0; f < 6; f++)
            if (f != face && f != other[0] && most[f] > 0 && (best < 0 || most[f] > most[best]))
                best = f;
        if (best < 0) break;
        other[count++] = best;
    }
    // Each other face's metres relative to a whole number of the far scale's periods
    // (the texture repeats there), taken at a vertex it weighs on. Vertices it does not
    // weigh on keep its coordinates where they extend, so that the ones between run on.
    for (int k = 0; k < count; k++) {
        const int f = other[k];
        int at = 0;
        while (!(weight[at][f] > 0))
            at++;
        double base[2];
        for (int a = 0; a < 2; a++)
            base[a] =
                floor((st[at][f][a] + 1.0) * 0.5 * face_metres / TEX_PERIOD_FAR) * TEX_PERIOD_FAR;
        for (int q = 0; q < GRID_VERTS; q++) {
            float *o = out + (size_t)q * VERTEX_FLOATS + BLEND_FLOAT0 + 3 * k;
            if (!on[q][f]) continue;
            o[0] = (float)((st[q][f][0] + 1.0) * 0.5 * face_metres - base[0]);
            o[1] = (float)((st[q][f][1] + 1.0) * 0.5 * face_metres - base[1]);
            o[2] = (float)weight[q][f];
        }
    }
    return count;
}
