// Layer masks (editor/layers/layer_mask.h): each term against its formula on plain arrays
// and on analytic surfaces (a cone's slope, a paraboloid's curvature, a V-valley's flow),
// independence from where the evaluation window is cut, the text round trip, bad input.
#include "editor/layers/layer_mask.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

// |a - b| <= tol, naming both values when not.
#define assert_near(a, b, tol)                                                                     \
    do {                                                                                           \
        double a_ = (a), b_ = (b);                                                                 \
        if (!(fabs(a_ - b_) <= (tol))) fail_msg("%s = %.9g, wanted %.9g", #a, a_, b_);             \
    } while (0)

static uint64_t rng_state = 0x9e3779b97f4a7c15ull;
static double rnd(void) { // 0..1, reproducible
    rng_state ^= rng_state << 13, rng_state ^= rng_state >> 7, rng_state ^= rng_state << 17;
    return (double)(rng_state >> 11) / 9007199254740992.0;
}

static layer_mask mask_of(const char *text) {
    layer_mask m;
    layer_mask_init(&m);
    og_error err = {{0}};
    if (layer_mask_parse(&m, text, &err)) fail_msg("'%s': %s", text, err.msg);
    return m;
}

// The window (area + border) of a big row-major array whose area starts at (x0, y0).
static float *window_of(const float *big, int big_w, int x0, int y0, int w, int h, int b) {
    int ww = w + 2 * b, wh = h + 2 * b;
    float *win = malloc(sizeof *win * (size_t)ww * (size_t)wh);
    for (int y = 0; y < wh; y++)
        memcpy(win + (size_t)y * ww, big + (size_t)(y0 - b + y) * big_w + (x0 - b),
               sizeof *win * (size_t)ww);
    return win;
}

static void test_no_mask_is_one(void **state) {
    (void)state;
    layer_mask m;
    layer_mask_init(&m);
    assert_false(layer_mask_active(&m));
    assert_int_equal(layer_mask_border(&m, 1.0), 0);
    float below[9] = {1, 2, 3, 4, 5, 6, 7, 8, 9}, out[9];
    layer_mask_evaluate(&m, below, 3, 3, 0, 1.0, NULL, out);
    for (int i = 0; i < 9; i++)
        assert_true(out[i] == 1.0f);
    char text[16] = "junk";
    assert_int_equal(layer_mask_format(&m, text, sizeof text), 0);
    assert_string_equal(text, "");
}

static void test_borders(void **state) {
    (void)state;
    assert_int_equal(layer_mask_border(&(layer_mask){.height.on = 1}, 2.0), 0);
    layer_mask s = mask_of("slope=0,30");
    assert_int_equal(layer_mask_border(&s, 2.0), 1);
    layer_mask c = mask_of("curvature=-1,1 height=0,10");
    assert_int_equal(layer_mask_border(&c, 2.0), 1);
    layer_mask f = mask_of("flow=100,1e9 slope=0,30");
    assert_int_equal(layer_mask_border(&f, 2.0), LAYER_MASK_FLOW_BORDER);
    layer_mask i = mask_of("invert=1");
    assert_true(layer_mask_active(&i));
    assert_int_equal(layer_mask_border(&i, 2.0), 0);
}

// The smoothstep edge at known points: half way through the edge is 0.5.
static void test_edges(void **state) {
    (void)state;
    layer_mask m = mask_of("height=100,200 falloff=50");
    double v[] = {0, 49.999, 50, 62.5, 75, 100, 150, 200, 225, 250, 1e9, -INFINITY};
    double want[] = {0, 0, 0, 0.15625, 0.5, 1, 1, 1, 0.5, 0, 0, 0};
    for (size_t i = 0; i < sizeof v / sizeof v[0]; i++)
        assert_near(layer_mask_range_weight(&m.height, v[i]), want[i], 1e-12);
    layer_mask hard = mask_of("slope=10,20");
    assert_true(layer_mask_range_weight(&hard.slope, 9.9999) == 0);
    assert_true(layer_mask_range_weight(&hard.slope, 10) == 1);
    assert_true(layer_mask_range_weight(&hard.slope, 20) == 1);
    assert_true(layer_mask_range_weight(&hard.slope, 20.0001) == 0);
    layer_mask open = mask_of("height=-inf,300");
    assert_true(layer_mask_range_weight(&open.height, -1e30) == 1);
    assert_true(layer_mask_range_weight(&open.height, 301) == 0);
}

// Every term on random heights against its formula written out here, and the product.
static void test_terms_match_formulas(void **state) {
    (void)state;
    enum { W = 23, H = 17, B = 2 };
    int ww = W + 2 * B, wh = H + 2 * B;
    float below[(W + 2 * B) * (H + 2 * B)], painted[W * H], out[W * H];
    for (int i = 0; i < ww * wh; i++)
        below[i] = (float)(rnd() * 40.0);
    for (int i = 0; i < W * H; i++)
        painted[i] = (float)(rnd() * 1.4 - 0.2);
    const double s = 2.5;
    layer_mask m = mask_of("height=5,35 falloff=4 slope=10,80,6 curvature=-300,250,40 painted=1");
    layer_mask_evaluate(&m, below, W, H, B, s, painted, out);
    layer_mask inv = m;
    inv.invert = 1;
    float out_inv[W * H];
    layer_mask_evaluate(&inv, below, W, H, B, s, painted, out_inv);
    int partial = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
#define Z(dx, dy) ((double)below[(y + B + (dy)) * ww + (x + B + (dx))])
            double gx = (Z(1, 0) - Z(-1, 0)) / (2 * s), gy = (Z(0, 1) - Z(0, -1)) / (2 * s);
            double slope = atan(sqrt(gx * gx + gy * gy)) * 180 / M_PI;
            double curv = -100 * (Z(1, 0) + Z(-1, 0) + Z(0, 1) + Z(0, -1) - 4 * Z(0, 0)) / (s * s);
            double hw = layer_mask_range_weight(&m.height, Z(0, 0));
#undef Z
            double sw = layer_mask_range_weight(&m.slope, slope);
            double cw = layer_mask_range_weight(&m.curvature, curv);
            double p = painted[y * W + x] < 0 ? 0 : painted[y * W + x] > 1 ? 1 : painted[y * W + x];
            double want = hw * sw * cw * p;
            assert_near(out[y * W + x], want, 1e-5);
            assert_near(out_inv[y * W + x], 1 - want, 1e-5);
            if (want > 0.05 && want < 0.95) partial++;
        }
    assert_true(partial > 10); // the soft edges were exercised, not only 0 and 1
    // painted without coverage is nowhere
    layer_mask_evaluate(&m, below, W, H, B, s, NULL, out);
    for (int i = 0; i < W * H; i++)
        assert_true(out[i] == 0);
}

// The slope term's shortcut (weights 1 and 0 decided on the rise over run, the atan only
// on the soft edges) gives bit for bit the weights of the slope in degrees: random
// ranges (hard and soft edges, open ends, 0 and 90) over random ground, steep and gentle.
static void test_slope_shortcut_exact(void **state) {
    (void)state;
    enum { W = 31, H = 29, B = 1 };
    int ww = W + 2 * B, wh = H + 2 * B;
    float below[(W + 2 * B) * (H + 2 * B)], degrees[W * H], out[W * H];
    int soft = 0;
    for (int round = 0; round < 600; round++) {
        double relief = round % 3 == 0 ? 2.0 : round % 3 == 1 ? 30.0 : 400.0;
        double spacing = 1 + rnd() * 9;
        for (int i = 0; i < ww * wh; i++)
            below[i] = (float)(rnd() * relief);
        if (round % 7 == 0) below[40] = NAN;
        layer_mask m;
        layer_mask_init(&m);
        double lo = rnd() < 0.2 ? 0 : rnd() * 90, hi = rnd() < 0.2 ? 90 : lo + rnd() * (90 - lo);
        double edge = rnd() < 0.3 ? 0 : rnd() * 20;
        m.slope = (layer_mask_range){.on = 1, .lo = lo, .hi = hi, .edge = edge};
        layer_mask_evaluate(&m, below, W, H, B, spacing, NULL, out);
        layer_mask_slope_degrees(below, W, H, B, spacing, degrees);
        for (int i = 0; i < W * H; i++) {
            float want = (float)layer_mask_range_weight(&m.slope, degrees[i]);
            if (memcmp(&out[i], &want, sizeof want))
                fail_msg("slope=%.9g,%.9g,%.9g at %.9g degrees: %.9g, wanted %.9g", lo, hi, edge,
                         degrees[i], out[i], want);
            soft += want > 0 && want < 1;
        }
    }
    assert_true(soft > 1000); // the soft edges were exercised, not only 0 and 1
}

// A cone h = 500 - k r: the slope is atan(k) everywhere off the apex.
static void test_cone_slope(void **state) {
    (void)state;
    enum { N = 101 };
    static float below[N * N], slope[(N - 2) * (N - 2)];
    const double s = 3.0, k = 0.7;
    for (int y = 0; y < N; y++)
        for (int x = 0; x < N; x++)
            below[y * N + x] = (float)(500 - k * s * hypot(x - 50, y - 50));
    layer_mask_slope_degrees(below, N - 2, N - 2, 1, s, slope);
    double want = atan(k) * 180 / M_PI, worst = 0;
    for (int y = 0; y < N - 2; y++)
        for (int x = 0; x < N - 2; x++) {
            double r = hypot(x + 1 - 50, y + 1 - 50);
            if (r < 15) continue; // near the apex central differences cut across the level rings
            worst = fmax(worst, fabs(slope[y * (N - 2) + x] - want));
        }
    print_message("cone: slope %.4f deg, worst error %.2g deg\n", want, worst);
    assert_true(worst < 0.05);
    // A mask of slope 30..40 (atan 0.7 = 35 deg) keeps the cone's flanks.
    layer_mask m = mask_of("slope=30,40");
    static float out[(N - 2) * (N - 2)];
    layer_mask_evaluate(&m, below, N - 2, N - 2, 1, s, NULL, out);
    assert_true(out[10 * (N - 2) + 10] == 1 && out[49 * (N - 2) + 49] == 0);
}

// A paraboloid h = c - a r^2: the curvature is 400 a everywhere; its bowl reads -400 a.
static void test_paraboloid_curvature(void **state) {
    (void)state;
    enum { N = 64 };
    static float dome[N * N], bowl[N * N], c[(N - 2) * (N - 2)];
    const double s = 2.0, a = 0.004;
    for (int y = 0; y < N; y++)
        for (int x = 0; x < N; x++) {
            double r2 = (pow((x - 31.5) * s, 2) + pow((y - 31.5) * s, 2));
            dome[y * N + x] = (float)(200 - a * r2);
            bowl[y * N + x] = (float)(-50 + a * r2);
        }
    layer_mask_curvature(dome, N - 2, N - 2, 1, s, c);
    for (int i = 0; i < (N - 2) * (N - 2); i++)
        assert_near(c[i], 400 * a, 2e-3);
    layer_mask_curvature(bowl, N - 2, N - 2, 1, s, c);
    for (int i = 0; i < (N - 2) * (N - 2); i++)
        assert_near(c[i], -400 * a, 2e-3);
    // convex only: the dome is in, the bowl is out
    layer_mask m = mask_of("curvature=0.5,inf");
    layer_mask_evaluate(&m, dome, N - 2, N - 2, 1, s, NULL, c);
    assert_true(c[0] == 1 && c[500] == 1);
    layer_mask_evaluate(&m, bowl, N - 2, N - 2, 1, s, NULL, c);
    assert_true(c[0] == 0 && c[500] == 0);
}

// A V-valley running down +y: flow grows downstream along the thalweg, close to the
// area of the rows above; the flanks carry far less.
static void test_valley_flow(void **state) {
    (void)state;
    enum { N = 81 };
    static float below[N * N], flow[N * N];
    const double s = 5.0, side = 0.3, fall = 0.05;
    for (int y = 0; y < N; y++)
        for (int x = 0; x < N; x++)
            below[y * N + x] = (float)(1000 + side * s * abs(x - 40) - fall * s * y);
    assert_int_equal(layer_mask_flow_area(below, N, N, 0, s, flow), 0);
    double previous = 0;
    for (int y = 0; y < N; y++) {
        double thalweg = flow[y * N + 40];
        assert_true(thalweg > previous);
        previous = thalweg;
        // Everything above the row (side streams join a few rows lower: 0.05/0.3 per column).
        if (y >= 20 && y < N - 1) {
            double above = (double)N * (y + 1) * s * s;
            assert_true(thalweg > 0.7 * above && thalweg <= above * 1.0001);
        }
        // A flank sample halfway up carries only the slope above it across the flank.
        if (y > 10) assert_true(flow[y * N + 20] < thalweg / 10);
    }
    print_message("valley: thalweg %.0f m^2 at the bottom row of %d x %d cells of %.0f m^2\n",
                  previous, N, N, s * s);
    // The mask: flow above 20 cells' area keeps the valley floor only.
    layer_mask m = mask_of("flow=500,inf,100");
    static float out[N * N];
    layer_mask_evaluate(&m, below, N, N, 0, s, NULL, out);
    assert_true(out[60 * N + 40] == 1 && out[60 * N + 10] == 0 && out[60 * N + 70] == 0);
}

// Smooth random hills: value noise, three octaves, on a plane falling tilt metres per
// sample towards +x (half that towards +y), so that water runs far instead of pooling.
static float *hills(int n, double amplitude, double tilt) {
    enum { G = 64 };
    static double lattice[3][G][G];
    for (int o = 0; o < 3; o++)
        for (int j = 0; j < G; j++)
            for (int i = 0; i < G; i++)
                lattice[o][j][i] = rnd();
    float *z = malloc(sizeof *z * (size_t)n * (size_t)n);
    for (int y = 0; y < n; y++)
        for (int x = 0; x < n; x++) {
            double v = 0;
            for (int o = 0; o < 3; o++) {
                double f = (double)(G - 2) / n * (1 << o) / 4, u = x * f, w = y * f;
                int i = (int)u, j = (int)w;
                double a = u - i, b = w - j;
                a = a * a * (3 - 2 * a), b = b * b * (3 - 2 * b);
                i %= G - 1, j %= G - 1;
                double top = lattice[o][j][i] * (1 - a) + lattice[o][j][i + 1] * a;
                double bottom = lattice[o][j + 1][i] * (1 - a) + lattice[o][j + 1][i + 1] * a;
                v += (top * (1 - b) + bottom * b) * amplitude / (1 << o);
            }
            z[(size_t)y * n + x] = (float)(v - tilt * (x + 0.5 * y));
        }
    return z;
}

// Where the window is cut: slope and curvature are bit-exact; flow, which sees only the
// border's context, agrees with the whole map's flow wherever the mask's threshold is
// within the border's reach, and its weights differ on a few samples at most.
static void test_window_independence(void **state) {
    (void)state;
    enum { N = 640, A = 48 };
    const int b = LAYER_MASK_FLOW_BORDER;
    const double s = 4.0;
    float *big = hills(N, 120.0, 1.0);
    // The truth: one evaluation over the whole map, the areas far inside it.
    layer_mask m = mask_of("flow=2000,inf,1500 slope=0,25,3 curvature=-2,inf,0.5");
    layer_mask flow_only = mask_of("flow=2000,inf,1500");
    int inner = N - 2 * 192;
    float *truth = malloc(sizeof *truth * (size_t)inner * inner);
    float *truth_flow = malloc(sizeof *truth * (size_t)inner * inner);
    layer_mask_evaluate(&m, big, inner, inner, 192, s, NULL, truth);
    layer_mask_evaluate(&flow_only, big, inner, inner, 192, s, NULL, truth_flow);
    float *truth_area = malloc(sizeof *truth * (size_t)inner * inner);
    assert_int_equal(layer_mask_flow_area(big, inner, inner, 192, s, truth_area), 0);
    long compared = 0, differ = 0, differ_flow = 0, differ_area = 0;
    double biggest = 0;
    double worst = 0;
    for (int trial = 0; trial < 24; trial++) {
        int x0 = 192 + (int)(rnd() * (inner - A)), y0 = 192 + (int)(rnd() * (inner - A));
        float *win = window_of(big, N, x0, y0, A, A, b);
        float out[A * A], out_flow[A * A], slope_win[A * A], slope_big[A * A], area[A * A];
        assert_int_equal(layer_mask_flow_area(win, A, A, b, s, area), 0);
        layer_mask_evaluate(&m, win, A, A, b, s, NULL, out);
        layer_mask_evaluate(&flow_only, win, A, A, b, s, NULL, out_flow);
        // The local terms do not depend on the window at all.
        float *near = window_of(big, N, x0, y0, A, A, 1);
        layer_mask_slope_degrees(win, A, A, b, s, slope_win);
        layer_mask_slope_degrees(near, A, A, 1, s, slope_big);
        assert_memory_equal(slope_win, slope_big, sizeof slope_win);
        free(near);
        for (int y = 0; y < A; y++)
            for (int x = 0; x < A; x++) {
                size_t t = (size_t)(y0 - 192 + y) * inner + (x0 - 192 + x);
                double d = fabs(out[y * A + x] - truth[t]);
                worst = fmax(worst, d);
                differ += d > 0.02;
                differ_flow += fabs(out_flow[y * A + x] - truth_flow[t]) > 0.02;
                differ_area += fabs(area[y * A + x] - truth_area[t]) > 0.01 * truth_area[t];
                biggest = fmax(biggest, truth_area[t]);
                compared++;
            }
        free(win);
    }
    print_message("window cuts: %ld samples, %ld (%.3f%%) differ by > 0.02 (flow alone %ld), "
                  "worst %.3f; flow areas off by > 1%%: %ld (largest area %.0f m^2)\n",
                  compared, differ, 100.0 * differ / compared, differ_flow, worst, differ_area,
                  biggest);
    assert_true(differ_area > 0); // the cut is real: long catchments lose their far part
    assert_true(differ_area <= compared / 200);
    assert_true(differ <= compared / 200); // at most 0.5% of samples
    // The comparison means something: the flow term is partial over much of the map.
    long in_flow = 0;
    for (long i = 0; i < (long)inner * inner; i++)
        in_flow += truth_flow[i] > 0.5;
    assert_true(in_flow > (long)inner * inner / 50 && in_flow < (long)inner * inner / 2);
    free(truth), free(truth_flow), free(truth_area), free(big);
}

// Random masks survive format + parse bit for bit.
static void test_round_trip(void **state) {
    (void)state;
    const double specials[] = {-INFINITY, INFINITY, 0.0, -0.0, 1e-300, 0.1, 1.0 / 3, 8848.86};
    for (int trial = 0; trial < 2000; trial++) {
        layer_mask m;
        layer_mask_init(&m);
        layer_mask_range *terms[4] = {&m.height, &m.slope, &m.curvature, &m.flow};
        for (int t = 0; t < 4; t++) {
            if (rnd() < 0.4) continue;
            double a = rnd() < 0.2 ? specials[(int)(rnd() * 8)] : (rnd() - 0.3) * 1e4;
            double b2 = rnd() < 0.2 ? specials[(int)(rnd() * 8)] : (rnd() - 0.3) * 1e4;
            if (t == 1 || t == 3) a = fabs(a), b2 = fabs(b2);
            if (t == 1) a = fmin(a, 90), b2 = fmin(b2, 90);
            if (a > b2) {
                double c = a;
                a = b2, b2 = c;
            }
            terms[t]->on = 1, terms[t]->lo = a, terms[t]->hi = b2;
            if (t > 0 && rnd() < 0.5) terms[t]->edge = rnd() * 30;
        }
        if (rnd() < 0.5) m.height.edge = rnd() * 100;
        m.invert = rnd() < 0.3, m.painted = rnd() < 0.3;
        char text[512];
        int n = layer_mask_format(&m, text, sizeof text);
        assert_true(n < (int)sizeof text);
        assert_int_equal(n, (int)strlen(text));
        layer_mask back;
        layer_mask_init(&back);
        og_error err = {{0}};
        if (layer_mask_parse(&back, text, &err)) fail_msg("'%s': %s", text, err.msg);
        layer_mask_range *backs[4] = {&back.height, &back.slope, &back.curvature, &back.flow};
        for (int t = 0; t < 4; t++) {
            assert_int_equal(backs[t]->on, terms[t]->on);
            assert_memory_equal(&backs[t]->lo, &terms[t]->lo, sizeof(double));
            assert_memory_equal(&backs[t]->hi, &terms[t]->hi, sizeof(double));
            assert_memory_equal(&backs[t]->edge, &terms[t]->edge, sizeof(double));
        }
        assert_int_equal(back.invert, m.invert);
        assert_int_equal(back.painted, m.painted);
        // A short buffer is cut and says how long the whole is.
        char small[8];
        assert_int_equal(layer_mask_format(&m, small, sizeof small), n);
        assert_true(strlen(small) < sizeof small);
    }
    layer_mask m = mask_of("height=0,1 slope=1,2,3 flow=4,5");
    char text[128];
    layer_mask_format(&m, text, sizeof text);
    assert_string_equal(text, "height=0,1 slope=1,2,3 flow=4,5");
    // off removes a term; the height's falloff stays apart from it
    assert_int_equal(layer_mask_parse(&m, "slope=off falloff=7 height=off", NULL), 0);
    layer_mask_format(&m, text, sizeof text);
    assert_string_equal(text, "flow=4,5 falloff=7");
}

// Bad values are refused with the key and the value named, the mask left as it was.
static void test_bad_inputs(void **state) {
    (void)state;
    const struct {
        const char *key, *value, *says;
    } bad[] = {
        {"height", "nan,5", "height=nan,5: expected LO,HI"},
        {"height", "1,nan", "height=1,nan"},
        {"height", "300,200", "height=300,200: the low end 300 is above the high end 200"},
        {"height", "1,2,3", "its edge width is falloff=M"},
        {"height", "", "height=: expected"},
        {"height", "5", "height=5: expected LO,HI"},
        {"height", "1,,2", "height=1,,2"},
        {"height", "1x,2", "height=1x,2"},
        {"slope", "10,95", "slope=10,95: degrees must lie within 0..90"},
        {"slope", "-5,10", "slope=-5,10"},
        {"slope", "10,20,-1", "slope=10,20,-1: the edge width -1 must be a number >= 0"},
        {"slope", "10,20,inf", "slope=10,20,inf"},
        {"slope", "1,2,3,4", "slope=1,2,3,4"},
        {"curvature", "2,-2", "curvature=2,-2: the low end 2 is above"},
        {"flow", "-1,10", "flow=-1,10"},
        {"falloff", "-3", "falloff=-3: expected metres >= 0"},
        {"falloff", "nan", "falloff=nan"},
        {"falloff", "inf", "falloff=inf"},
        {"invert", "2", "invert=2: expected 0 or 1"},
        {"painted", "yes", "painted=yes: expected 0 or 1"},
        {"hieght", "0,1", "hieght=0,1: unknown mask key"},
    };
    layer_mask m = mask_of("height=0,100 slope=5,10,1 falloff=3 invert=1");
    layer_mask before = m;
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        og_error err = {{0}};
        assert_int_equal(layer_mask_set_option(&m, bad[i].key, bad[i].value, &err), -1);
        if (!strstr(err.msg, bad[i].says))
            fail_msg("%s=%s said '%s', wanted '%s'", bad[i].key, bad[i].value, err.msg,
                     bad[i].says);
        assert_memory_equal(&m, &before, sizeof m);
    }
    og_error err = {{0}};
    assert_int_equal(layer_mask_parse(&m, "slope=1,2 bogus", &err), -1);
    assert_non_null(strstr(err.msg, "'bogus' is not key=value"));
    assert_int_equal(layer_mask_parse(&m, "slope=1,2 height=9,1", &err), -1);
    assert_memory_equal(&m, &before, sizeof m); // the good slope did not land either
}

// Too little border degrades to one-sided differences instead of reading outside.
static void test_short_border(void **state) {
    (void)state;
    float ramp[4 * 3], out[4 * 3];
    for (int y = 0; y < 3; y++)
        for (int x = 0; x < 4; x++)
            ramp[y * 4 + x] = (float)(x * 2.0);
    layer_mask_slope_degrees(ramp, 4, 3, 0, 2.0, out);
    for (int i = 0; i < 12; i++)
        assert_near(out[i], 45.0, 1e-4);
    layer_mask_curvature(ramp, 4, 3, 0, 2.0, out);
    for (int y = 0; y < 3; y++)
        for (int x = 1; x < 3; x++)
            assert_near(out[y * 4 + x], 0, 1e-9);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_no_mask_is_one), cmocka_unit_test(test_borders),
        cmocka_unit_test(test_edges),          cmocka_unit_test(test_terms_match_formulas),
        cmocka_unit_test(test_cone_slope),     cmocka_unit_test(test_paraboloid_curvature),
        cmocka_unit_test(test_valley_flow),    cmocka_unit_test(test_window_independence),
        cmocka_unit_test(test_round_trip),     cmocka_unit_test(test_bad_inputs),
        cmocka_unit_test(test_short_border),   cmocka_unit_test(test_slope_shortcut_exact),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
