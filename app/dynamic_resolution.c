#include "app/dynamic_resolution.h"

#include <math.h>

float dynamic_resolution_next(float scale, double frame_ms, double target_ms) {
    // Aim a little under the goal, so frames that vary a little still meet it.
    float next = scale * sqrtf((float)(0.9 * target_ms / fmax(frame_ms, 1.0)));
    return fminf(1.0f, fmaxf(DYNAMIC_RESOLUTION_MIN, 0.5f * (scale + next)));
}
