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
    glProgramUniform3f(prog, glGetUniformLocation(prog, "u_sun_colour"), 1.05f,
                       0.97f * warm + 0.03f, 0.86f * warm + 0.05f);
    glProgramUniform3f(prog, glGetUniformLocation(prog, "u_sky_zenith"), 0.24f, 0.43f, 0.74f);
    glProgramUniform3f(prog, glGetUniformLocation(prog, "u_sky_horizon"), 0.70f, 0.78f, 0.86f);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_fog_density"), (float)fog_density);
}

void render_sky(GLuint prog, GLuint empty_vao, const camera *cam, const render_settings *s,
                double aspect, double fog_density) {
    double f[3], rt[3], up[3];
    camera_forward(cam, f), camera_right(cam, rt), camera_up(cam, up);
    glProgramUniform3f(prog, glGetUniformLocation(prog, "u_cam_forward"), (float)f[0], (float)f[1],
                       (float)f[2]);
    glProgramUniform3f(prog, glGetUniformLocation(prog, "u_cam_right"), (float)rt[0], (float)rt[1],
                       (float)rt[2]);
    glProgramUniform3f(prog, glGetUniformLocation(prog, "u_cam_up"), (float)up[0], (float)up[1],
                       (float)up[2]);
    double ty = tan(cam->fov_y * M_PI / 360.0);
    glProgramUniform2f(prog, glGetUniformLocation(prog, "u_tan_half"), (float)(ty * aspect),
                       (float)ty);
    render_lighting_uniforms(prog, s, fog_density);
    glUseProgram(prog);
    glBindVertexArray(empty_vao);
    glDepthMask(GL_FALSE);
    glDisable(GL_DEPTH_TEST);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
}
