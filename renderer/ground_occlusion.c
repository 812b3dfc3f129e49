#include "renderer/ground_occlusion.h"

#include <math.h>
#include <stdlib.h>

enum { COLUMNS = GROUND_OCCLUSION_COLUMNS, BANDS = GROUND_OCCLUSION_BANDS, MAX_POINTS = 8 };

static double dot(const double a[3], const double b[3]) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

void ground_occlusion_begin(ground_occlusion *o, const double eye[3], const double forward[3],
                            const double right[3], const double up[3], double tan_half_x,
                            double tan_half_y) {
    for (int k = 0; k < 3; k++)
        o->eye[k] = eye[k], o->forward[k] = forward[k], o->right[k] = right[k], o->up[k] = up[k];
    o->tan_half_x = tan_half_x, o->tan_half_y = tan_half_y;
    for (int i = 0; i < COLUMNS; i++) // every band alike: none covered
        o->top[i] = 0, o->lo[i][0] = INFINITY, o->hi[i][0] = -INFINITY;
}

// Screen points: x in columns (0 at the left edge), y from -1 (bottom) to 1 (top); the
// nearest and farthest points' depths along the view (what orders two points on one
// pixel's ray). 0 when a point is not in front of the camera.
static int project(const ground_occlusion *o, const double (*pts)[3], int n, double out[][2],
                   double *nearest, double *farthest) {
    *nearest = INFINITY, *farthest = 0;
    for (int k = 0; k < n; k++) {
        const double d[3] = {pts[k][0] - o->eye[0], pts[k][1] - o->eye[1], pts[k][2] - o->eye[2]};
        const double z = dot(d, o->forward), dist = sqrt(dot(d, d));
        if (!(z > 1e-6 * dist)) return 0;
        out[k][0] = (dot(d, o->right) / (z * o->tan_half_x) + 1.0) * 0.5 * COLUMNS;
        out[k][1] = dot(d, o->up) / (z * o->tan_half_y);
        *nearest = fmin(*nearest, z), *farthest = fmax(*farthest, z);
    }
    return 1;
}

static int by_x(const void *a, const void *b) {
    const double *p = a, *q = b;
    return p[0] < q[0] ? -1 : p[0] > q[0] ? 1 : (p[1] > q[1]) - (p[1] < q[1]);
}

static double cross(const double o[2], const double a[2], const double b[2]) {
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

// The convex hull, counter-clockwise (Andrew's monotone chain); returns its size.
static int hull(double p[][2], int n, double out[][2]) {
    qsort(p, (size_t)n, sizeof p[0], by_x);
    int k = 0;
    for (int i = 0; i < n; i++) {
        while (k >= 2 && cross(out[k - 2], out[k - 1], p[i]) <= 0)
            k--;
        out[k][0] = p[i][0], out[k][1] = p[i][1], k++;
    }
    for (int i = n - 2, lower = k + 1; i >= 0; i--) {
        while (k >= lower && cross(out[k - 2], out[k - 1], p[i]) <= 0)
            k--;
        out[k][0] = p[i][0], out[k][1] = p[i][1], k++;
    }
    return k - 1;
}

// Minimum and maximum of numbers (never NaN here) without libm's calls.
static double min_d(double a, double b) {
    return a < b ? a : b;
}

static double max_d(double a, double b) {
    return a > b ? a : b;
}

// The hull's vertical extent at x; 0 when the line misses it.
static int span_at(const double h[][2], int n, double x, double *lo, double *hi) {
    *lo = INFINITY, *hi = -INFINITY;
    for (int k = 0; k < n; k++) {
        const double *a = h[k], *b = h[(k + 1) % n];
        if ((x < a[0] && x < b[0]) || (x > a[0] && x > b[0])) continue;
        double y = a[0] == b[0] ? a[1] : a[1] + (b[1] - a[1]) * (x - a[0]) / (b[0] - a[0]);
        if (a[0] == b[0]) *lo = min_d(*lo, min_d(a[1], b[1])), *hi = max_d(*hi, max_d(a[1], b[1]));
        *lo = min_d(*lo, y), *hi = max_d(*hi, y);
    }
    return *lo <= *hi;
}

// The first band whose depth holds `depth` (BANDS when none does).
static int band_holding(double depth) {
    int b = depth <= 1.0 ? 0 : (int)ceil(log2(depth) * GROUND_OCCLUSION_BANDS_PER_OCTAVE);
    return b < BANDS ? b : BANDS;
}

void ground_occlusion_add_solid(ground_occlusion *o, const double (*pts)[3], int n) {
    double p[MAX_POINTS][2], h[MAX_POINTS + 1][2], nearest, farthest;
    if (n < 3 || n > MAX_POINTS || !project(o, pts, n, p, &nearest, &farthest)) return;
    const int m = hull(p, n, h);
    if (m < 3) return;
    const int first = band_holding(farthest);
    if (first >= BANDS) return;
    double minx = INFINITY, maxx = -INFINITY;
    for (int k = 0; k < m; k++)
        minx = fmin(minx, h[k][0]), maxx = fmax(maxx, h[k][0]);
    // Column i spans [i, i + 1]: covered where the hull holds both of its edges (and so,
    // being convex, everything between).
    const int i0 = (int)fmax(ceil(minx), 0), i1 = (int)fmin(floor(maxx), COLUMNS) - 1;
    double lo1, hi1; // the span at column i's right edge, the next one's left edge
    int at1 = i0 <= i1 && span_at(h, m, i0, &lo1, &hi1);
    for (int i = i0; i <= i1; i++) {
        const double lo0 = lo1, hi0 = hi1;
        const int at0 = at1;
        at1 = span_at(h, m, i + 1, &lo1, &hi1);
        if (!at0 || !at1) continue;
        const float lo = (float)max_d(lo0, lo1), hi = (float)min_d(hi0, hi1);
        if (!(lo < hi)) continue;
        // Per band: above the covered run (or none yet: lo > -infinity), the horizon's side
        // replaces it; below it, it stays; else they overlap and become one run. As two
        // selects without branches, so that the compiler does several bands at once.
        float *col_lo = o->lo[i], *col_hi = o->hi[i];
        int top = o->top[i];
        if (first > top) { // the bands before this solid's keep what all held
            for (int b = top + 1; b <= first; b++)
                col_lo[b] = col_lo[top], col_hi[b] = col_hi[top];
            o->top[i] = (unsigned char)(top = first);
        }
        for (int b = first; b <= top; b++) {
            const float cl = col_lo[b], ch = col_hi[b];
            const int above = lo > ch, overlap = !(hi < cl);
            col_lo[b] = above | (overlap & (lo < cl)) ? lo : cl;
            col_hi[b] = above | (overlap & (hi > ch)) ? hi : ch;
        }
    }
}

int ground_occlusion_hidden(const ground_occlusion *o, const double (*pts)[3], int n) {
    double p[MAX_POINTS][2], nearest, farthest;
    if (n < 1 || n > MAX_POINTS || !project(o, pts, n, p, &nearest, &farthest)) return 0;
    double minx = INFINITY, maxx = -INFINITY, miny = INFINITY, maxy = -INFINITY;
    for (int k = 0; k < n; k++) {
        minx = fmin(minx, p[k][0]), maxx = fmax(maxx, p[k][0]);
        miny = fmin(miny, p[k][1]), maxy = fmax(maxy, p[k][1]);
    }
    if (maxx < 0 || minx >= COLUMNS || maxy < -1 || miny > 1) return 0;
    // Covered nearer than the hull's nearest point: the last band wholly nearer.
    const int band = band_holding(nearest) - 1;
    if (band < 0) return 0;
    const int b = band < BANDS ? band : BANDS - 1;
    const int i0 = (int)fmax(floor(minx), 0), i1 = (int)fmin(floor(maxx), COLUMNS - 1);
    const float lo = (float)fmax(miny, -1.0), hi = (float)fmin(maxy, 1.0); // what is on screen
    for (int i = i0; i <= i1; i++) {
        const int at = b < o->top[i] ? b : o->top[i];
        if (!(o->lo[i][at] <= lo && hi <= o->hi[i][at])) return 0;
    }
    return 1;
}
