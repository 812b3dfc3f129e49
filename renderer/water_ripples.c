#include "renderer/water_ripples.h"

#include <math.h>

// Radians per metre along x and z: wavelengths of about 36 m and 39 m, crossed, so the
// pattern does not repeat along any one direction within view.
static const double waves[2][2] = {{0.155, 0.085}, {-0.065, 0.145}};

void water_ripple_uniforms(GLuint prog, const double camera_pos[3]) {
    float phase[2];
    for (int k = 0; k < 2; k++) {
        double p = fmod(waves[k][0] * camera_pos[0] + waves[k][1] * camera_pos[2], 2.0 * M_PI);
        phase[k] = (float)(p < 0 ? p + 2.0 * M_PI : p);
    }
    glProgramUniform4f(prog, glGetUniformLocation(prog, "u_ripple_waves"), (float)waves[0][0],
                       (float)waves[0][1], (float)waves[1][0], (float)waves[1][1]);
    glProgramUniform2f(prog, glGetUniformLocation(prog, "u_ripple_phase"), phase[0], phase[1]);
}
