#include "renderer/lighting.h"

#include <math.h>

void render_sun_direction(const render_settings *s, float out[3]) {
    double yaw = s->sun_yaw * M_PI / 180.0, pitch = s->sun_pitch * M_PI / 180.0;
    out[0] = (float)(sin(yaw) * cos(pitch));
    out[1] = (float)sin(pitch);
    out[2] = (float)(-cos(yaw) * cos(pitch));
}

void render_lighting_uniforms(GLuint prog, const render_settings *s, double fog_density) {
    float sun[3];
    render_sun_direction(s, sun);
    glProgramUniform3fv(prog, glGetUniformLocation(prog, "u_sun_dir"), 1, sun);
    // A lower sun is warmer.
    float warm = (float)fmin(1.0, 0.35 + sun[1] * 2.0);
    glProgramUniform3f(prog, glGetUniformLocation(prog, "u_sun_colour"), 1.05f, 0.97f * warm + 0.03f,
                       0.86f * warm + 0.05f);
    glProgramUniform3f(prog, glGetUniformLocation(prog, "u_sky_zenith"), 0.24f, 0.43f, 0.74f);
    glProgramUniform3f(prog, glGetUniformLocation(prog, "u_sky_horizon"), 0.70f, 0.78f, 0.86f);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_fog_density"), (float)fog_density);
}
