#include "editor/tools/box_columns.h"

// A strip of up to 16 columns swept from top to bottom, both boxes' sums in registers
// and the first box's results in a ring of a few kilobytes: per row and column two
// adds and a subtract for each box (the double sums exact over any start that this
// replaced took five times the instructions, conversions included). The sums are not
// scaled to means here: the row boxes' last pass scales them once.

int64_t box_columns_anchor(int64_t y0, int k) {
    int64_t m = 2 * k + 1;
    return 2 * k + (y0 - 2 * k) / m * m;
}

// Lanes [0, n) of a strip at column x; the order of every column's operations is the
// one the AVX-512 strip below keeps.
static void strip_plain(const float *const *rows, float *const *out, const int64_t (*keep)[2],
                        int k, float *ring, int64_t x, int n, int64_t y0, int64_t y1) {
    const int64_t m = 2 * k + 1, slots = 2 * k + 2;
    float a1[16], d1[16], a2[16], d2[16];
    int64_t j0 = box_columns_anchor(y0, k), i0 = j0 - k;
    for (int64_t i = i0; i < y1 + k; i++) {
        float *b = ring + (i % slots) * 16;
        if ((i - k) % m == 0) { // the first box's rows [i - k, i + k]
            float p[4][16] = {{0}};
            for (int64_t r = 0; r <= 2 * k; r++)
                for (int l = 0; l < n; l++)
                    p[r & 3][l] = p[r & 3][l] + rows[i - k + r][x + l];
            for (int l = 0; l < n; l++)
                a1[l] = (p[0][l] + p[1][l]) + (p[2][l] + p[3][l]), d1[l] = 0.0f;
        } else {
            for (int l = 0; l < n; l++)
                d1[l] = d1[l] + (rows[i + k][x + l] - rows[i - k - 1][x + l]);
        }
        for (int l = 0; l < n; l++)
            b[l] = a1[l] + d1[l];
        int64_t j = i - k; // the second box's row whose last first-box row is i
        if (j < j0) continue;
        if ((j - 2 * k) % m == 0) { // the first box's rows [j - k, j + k]
            float p[4][16] = {{0}};
            for (int64_t r = 0; r <= 2 * k; r++)
                for (int l = 0; l < n; l++)
                    p[r & 3][l] = p[r & 3][l] + ring[((j - k + r) % slots) * 16 + l];
            for (int l = 0; l < n; l++)
                a2[l] = (p[0][l] + p[1][l]) + (p[2][l] + p[3][l]), d2[l] = 0.0f;
        } else {
            const float *old = ring + ((j - k - 1) % slots) * 16;
            for (int l = 0; l < n; l++)
                d2[l] = d2[l] + (b[l] - old[l]);
        }
        for (int l = 0; l < n; l++)
            if (!keep || (x + l >= keep[j][0] && x + l < keep[j][1])) out[j][x + l] = a2[l] + d2[l];
    }
}

void box_columns_plain(const float *const *rows, float *const *out, const int64_t (*keep)[2], int k,
                       float *ring, int64_t c0, int64_t c1, int64_t y0, int64_t y1) {
    if (y0 >= y1) return;
    for (int64_t x = c0; x < c1; x += 16)
        strip_plain(rows, out, keep, k, ring, x, c1 - x < 16 ? (int)(c1 - x) : 16, y0, y1);
}

// Not under ThreadSanitizer or other compilers (as HOT_LOOP): the plain loop runs.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_THREAD__)
#include <immintrin.h>

#define WIDE __attribute__((target("avx512f")))

#define INLINE __attribute__((target("avx512f"), always_inline)) static inline

// 16 floats at p, the lanes of m (full: all 16, as a plain load: a masked one takes an
// arithmetic port's slot too).
INLINE __m512 load(__mmask16 m, const float *p, int full) {
    return full ? _mm512_loadu_ps(p) : _mm512_maskz_loadu_ps(m, p);
}

// The first box's step for one strip (mask m, columns from x) at row i: its sum is
// a1 + d1, which sum gets.
INLINE void first_box(const float *const *rows, int64_t i, int k, int anchor, int64_t x,
                      __mmask16 m, int full, __m512 *a1, __m512 *d1, __m512 *sum) {
    if (anchor) { // rows [i - k, i + k] in four interleaved sums
        const float *const *v = rows + i - k;
        __m512 p0 = _mm512_setzero_ps(), p1 = p0, p2 = p0, p3 = p0;
        int64_t r = 0;
        for (; r + 3 <= 2 * k; r += 4) {
            p0 = _mm512_add_ps(p0, load(m, v[r] + x, full));
            p1 = _mm512_add_ps(p1, load(m, v[r + 1] + x, full));
            p2 = _mm512_add_ps(p2, load(m, v[r + 2] + x, full));
            p3 = _mm512_add_ps(p3, load(m, v[r + 3] + x, full));
        }
        p0 = _mm512_add_ps(p0, load(m, v[r] + x, full)); // 2k + 1 = 4q + 1 or 4q + 3
        if (r + 2 <= 2 * k) {
            p1 = _mm512_add_ps(p1, load(m, v[r + 1] + x, full));
            p2 = _mm512_add_ps(p2, load(m, v[r + 2] + x, full));
        }
        *a1 = _mm512_add_ps(_mm512_add_ps(p0, p1), _mm512_add_ps(p2, p3));
        *d1 = _mm512_setzero_ps();
    } else {
        __m512 in = load(m, rows[i + k] + x, full);
        __m512 gone = load(m, rows[i - k - 1] + x, full);
        *d1 = _mm512_add_ps(*d1, _mm512_sub_ps(in, gone));
    }
    *sum = _mm512_add_ps(*a1, *d1);
}

// The second box's step for one strip at row j (its last first-box row just made:
// sum; ring + q: its slot of row j - k - 1, the slots after it rows j - k ..).
INLINE __m512 second_box(const float *ring, int64_t q, int64_t slots, int k, int anchor, __m512 sum,
                         __m512 *a2, __m512 *d2) {
    if (anchor) { // the first box's rows [j - k, j + k]: the slots after q
        // the slots of rows j - k + r, r = 0 .. 2k: q + 1 + r, wrapping once
        const float *v[4];
        __m512 p0 = _mm512_setzero_ps(), p1 = p0, p2 = p0, p3 = p0;
        int64_t r = 0;
#define SLOT(r) (ring + (q + 1 + (r) < slots ? q + 1 + (r) : q + 1 + (r)-slots) * BOX_COLUMNS_WIDTH)
        for (; r + 3 <= 2 * k; r += 4) {
            v[0] = SLOT(r), v[1] = SLOT(r + 1), v[2] = SLOT(r + 2), v[3] = SLOT(r + 3);
            p0 = _mm512_add_ps(p0, _mm512_loadu_ps(v[0]));
            p1 = _mm512_add_ps(p1, _mm512_loadu_ps(v[1]));
            p2 = _mm512_add_ps(p2, _mm512_loadu_ps(v[2]));
            p3 = _mm512_add_ps(p3, _mm512_loadu_ps(v[3]));
        }
        p0 = _mm512_add_ps(p0, _mm512_loadu_ps(SLOT(r)));
        if (r + 2 <= 2 * k) {
            p1 = _mm512_add_ps(p1, _mm512_loadu_ps(SLOT(r + 1)));
            p2 = _mm512_add_ps(p2, _mm512_loadu_ps(SLOT(r + 2)));
        }
#undef SLOT
        *a2 = _mm512_add_ps(_mm512_add_ps(p0, p1), _mm512_add_ps(p2, p3));
        *d2 = _mm512_setzero_ps();
    } else {
        *d2 = _mm512_add_ps(*d2, _mm512_sub_ps(sum, _mm512_loadu_ps(ring + q * BOX_COLUMNS_WIDTH)));
    }
    return _mm512_add_ps(*a2, *d2);
}

enum { STRIPS = BOX_COLUMNS_WIDTH / 16 };

// What a sweep of up to STRIPS strips side by side shares.
typedef struct sweep {
    const float *const *rows;
    float *const *out;
    const int64_t (*keep)[2];
    float *ring;
    int64_t x, slots;
    int k;
} sweep;

// One strip's running sums and lanes. Each strip its own variable, named in each
// step (EACH): GCC keeps them in registers so; as one array they stayed on the stack,
// each running sum's step waiting on a store and a load.
typedef struct strip {
    __m512 a1, d1, a2, d2, sum, out;
    __m512i column; // each lane's column (areas are far narrower than 2^31)
    __mmask16 m;
} strip;

#define EACH(n, what)                                                                              \
    do {                                                                                           \
        what(0, t0);                                                                               \
        if (n > 1) what(1, t1);                                                                    \
        if (n > 2) what(2, t2);                                                                    \
        if (n > 3) what(3, t3);                                                                    \
    } while (0)

// One step at row i (ring slot at): the first box's row i; with second, the second
// box's row i - k. anchor1, anchor2: that box starts afresh here. n: the strips swept
// (t0 .. at x, x + 16, ..); full: every lane of them. Constants where inlined, so the
// steady steps run without branches.
INLINE void step(const sweep *s, int64_t i, int64_t at, int anchor1, int second, int anchor2,
                 const int n, int full, strip *t0, strip *t1, strip *t2, strip *t3) {
    float *b = s->ring + at * BOX_COLUMNS_WIDTH;
    int64_t next = at + 1 == s->slots ? 0 : at + 1;
#define FIRST(j, t)                                                                                \
    first_box(s->rows, i, s->k, anchor1, s->x + 16 * j, t->m, full, &t->a1, &t->d1, &t->sum)
    EACH(n, FIRST);
#undef FIRST
#define KEEP(j, t) _mm512_storeu_ps(b + 16 * j, t->sum)
    EACH(n, KEEP);
#undef KEEP
    if (!second) return;
#define SECOND(j, t)                                                                               \
    t->out = second_box(s->ring + 16 * j, next, s->slots, s->k, anchor2, t->sum, &t->a2, &t->d2)
    EACH(n, SECOND);
#undef SECOND
    float *to = s->out[i - s->k] + s->x;
    if (s->keep) { // only the row's kept columns: lanes whose column is in them
        const int64_t *c = s->keep[i - s->k];
        __m512i from = _mm512_set1_epi32((int)c[0]), to_end = _mm512_set1_epi32((int)c[1]);
#define KEPT(j, t)                                                                                 \
    _mm512_mask_storeu_ps(                                                                         \
        to + 16 * j,                                                                               \
        _mm512_mask_cmplt_epi32_mask(_mm512_mask_cmpge_epi32_mask(t->m, t->column, from),          \
                                     t->column, to_end),                                           \
        t->out)
        EACH(n, KEPT);
#undef KEPT
        return;
    }
#define WHOLE(j, t) _mm512_storeu_ps(to + 16 * j, t->out)
#define LANES(j, t) _mm512_mask_storeu_ps(to + 16 * j, t->m, t->out)
    if (full)
        EACH(n, WHOLE);
    else
        EACH(n, LANES);
#undef LANES
#undef WHOLE
}

// n strips side by side (strip j: columns [x + 16 j, x + 16 j + 16) by mask m[j]): their
// sums' additions, each a few cycles long, overlap, and each row's pointers, kept
// columns and loop steps serve all n. The anchors come in blocks of 2k + 1 steps of
// i: the first box's at the first step, the second box's at the last (j - 2k = i - 3k,
// a multiple of 2k + 1); the first block makes the first box's rows the second's first
// anchor takes.
INLINE void sweep_strips(const float *const *rows, float *const *out, const int64_t (*keep)[2],
                         int k, float *ring, int64_t x, const __mmask16 *m, int64_t y0, int64_t y1,
                         const int n, const int full) {
    const int64_t length = 2 * k + 1, slots = 2 * k + 2;
    const sweep s = {rows, out, keep, ring, x, slots, k};
    const __m512 zero = _mm512_setzero_ps();
    const __m512i lane = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    strip t0 = {zero, zero, zero, zero, zero, zero, lane, m[0]}, t1 = t0, t2 = t0, t3 = t0;
    t1.m = n > 1 ? m[1] : 0, t2.m = n > 2 ? m[2] : 0, t3.m = n > 3 ? m[3] : 0;
    t0.column = _mm512_add_epi32(lane, _mm512_set1_epi32((int)x));
    t1.column = _mm512_add_epi32(t0.column, _mm512_set1_epi32(16));
    t2.column = _mm512_add_epi32(t0.column, _mm512_set1_epi32(32));
    t3.column = _mm512_add_epi32(t0.column, _mm512_set1_epi32(48));
#define STEP(a1, second, a2) step(&s, i, at, a1, second, a2, n, full, &t0, &t1, &t2, &t3)
    int64_t i0 = box_columns_anchor(y0, k) - k, end = y1 + k, at = i0 % slots;
    for (int64_t i = i0; i < end;) {
        int64_t last = i + length - 1; // the block's last step
        int second = i > i0;
        if (second)
            STEP(1, 1, 0);
        else
            STEP(1, 0, 0);
        i++, at = at + 1 == slots ? 0 : at + 1;
        if (second)
            for (; i < last && i < end; i++, at = at + 1 == slots ? 0 : at + 1)
                STEP(0, 1, 0);
        else
            for (; i < last && i < end; i++, at = at + 1 == slots ? 0 : at + 1)
                STEP(0, 0, 0);
        if (i < end) {
            STEP(0, 1, 1);
            i++, at = at + 1 == slots ? 0 : at + 1;
        }
    }
#undef STEP
}
#undef EACH

// Each shape of sweep on its own code: 1 to 4 strips, without masks where every lane
// is swept.
#define SHAPE(n)                                                                                   \
    case n:                                                                                        \
        if (full)                                                                                  \
            sweep_strips(rows, out, keep, k, ring, x, m, y0, y1, n, 1);                            \
        else                                                                                       \
            sweep_strips(rows, out, keep, k, ring, x, m, y0, y1, n, 0);                            \
        break;

WIDE static void strips_wide(const float *const *rows, float *const *out, const int64_t (*keep)[2],
                             int k, float *ring, int64_t x, const __mmask16 *m, int n, int full,
                             int64_t y0, int64_t y1) {
    switch (n) {
        SHAPE(1)
        SHAPE(2)
        SHAPE(3)
        SHAPE(4)
    }
}
#undef SHAPE

int box_columns_have_wide(void) {
    return __builtin_cpu_supports("avx512f") != 0;
}

void box_columns(const float *const *rows, float *const *out, const int64_t (*keep)[2], int k,
                 float *ring, int64_t c0, int64_t c1, int64_t y0, int64_t y1) {
    if (!box_columns_have_wide()) {
        box_columns_plain(rows, out, keep, k, ring, c0, c1, y0, y1);
        return;
    }
    if (y0 >= y1) return;
    for (int64_t x = c0; x < c1; x += BOX_COLUMNS_WIDTH) {
        int64_t left = c1 - x;
        int n = left >= BOX_COLUMNS_WIDTH ? STRIPS : (int)((left + 15) / 16);
        __mmask16 m[STRIPS];
        for (int t = 0; t < n; t++) {
            int64_t lanes = left - 16 * t;
            m[t] = lanes >= 16 ? (__mmask16)0xffff : (__mmask16)((1u << lanes) - 1u);
        }
        strips_wide(rows, out, keep, k, ring, x, m, n, m[n - 1] == (__mmask16)0xffff, y0, y1);
    }
}
#else
int box_columns_have_wide(void) {
    return 0;
}

void box_columns(const float *const *rows, float *const *out, const int64_t (*keep)[2], int k,
                 float *ring, int64_t c0, int64_t c1, int64_t y0, int64_t y1) {
    box_columns_plain(rows, out, keep, k, ring, c0, c1, y0, y1);
}
#endif
