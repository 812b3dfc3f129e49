#include "app/brush_size.h"
#include <math.h>

enum { SAMPLES_ACROSS_TOP = 64, SAMPLES_ACROSS_AUTO_MIN = 2 };

double brush_radius_slider_max(double spacing) {
    return fmax(500.0, SAMPLES_ACROSS_TOP * spacing);
}

double brush_radius_key_max(double spacing) {
    return fmax(5000.0, SAMPLES_ACROSS_TOP * spacing);
}

double brush_radius_auto(double wanted, double spacing) {
    double lo = fmax(1.0, SAMPLES_ACROSS_AUTO_MIN * spacing);
    double r = fmin(fmax(wanted, lo), brush_radius_slider_max(spacing));
    double unit = pow(10.0, floor(log10(r)) - 1.0); // two significant digits
    r = round(r / unit) * unit;
    return r < lo ? r + unit : r;
}
