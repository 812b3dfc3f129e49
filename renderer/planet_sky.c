// Space, the sun and the atmosphere: the uniforms the sky and the ground share, and the
// sky drawn where no ground was.
#include "renderer/planet_internal.h"
#include "renderer/planet_renderer.h"

#include "renderer/lighting.h"
#include "renderer/planet_camera.h"

// Atmosphere and light uniforms shared by the sky and the ground.
void planet_set_common(const planet_renderer *r, GLuint prog, const camera *cam,
                       const render_settings *s) {
    const world_params *p = &r->params;
    double cam_r =
        sqrt(cam->pos[0] * cam->pos[0] + cam->pos[1] * cam->pos[1] + cam->pos[2] * cam->pos[2]);
    double e[3], n[3], up[3];
    planet_local_frame(cam->pos, e, n, up);
    float sun[3];
    render_sun_direction(s, sun);
    // Earth's Rayleigh scattering, its scale height scaled with the radius and the
    // coefficients scaled inversely, so any planet's sky is as thick as Earth's.
    const double hs = EARTH_SCALE_HEIGHT * p->radius / EARTH_RADIUS;
    double k = EARTH_SCALE_HEIGHT / hs;
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_radius"), (float)p->radius);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_scale_height"), (float)hs);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_atm_top"), (float)(hs * 10.0));
    k *= p->atmosphere; // 0: no air at all
    glProgramUniform3f(prog, glGetUniformLocation(prog, "u_beta"), (float)(5.8e-6 * k),
                       (float)(13.5e-6 * k), (float)(33.1e-6 * k));
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_cam_r"), (float)cam_r);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_cam_alt"), (float)(cam_r - p->radius));
    glProgramUniform3f(prog, glGetUniformLocation(prog, "u_cam_up"), (float)up[0], (float)up[1],
                       (float)up[2]);
    glProgramUniform3fv(prog, glGetUniformLocation(prog, "u_sun_dir"), 1, sun);
    glProgramUniform3f(prog, glGetUniformLocation(prog, "u_sun_colour"), 1.05f, 1.0f, 0.95f);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_view_mode"), s->view);
}

// Space, the sun and the sky, drawn after the ground where nothing was drawn: the
// fullscreen triangle lies on the far plane (depth 0) and passes only where the depth
// buffer still holds its clear value, so ground pixels never run the sky's integral.
void planet_draw_sky(planet_renderer *r, const camera *cam, const render_settings *s,
                     double aspect) {
    double f[3], rt[3], up[3];
    planet_camera_basis(cam, f, rt, up);
    GLuint prog = r->prog_sky;
    planet_set_common(r, prog, cam, s);
    glProgramUniform3f(prog, glGetUniformLocation(prog, "u_cam_forward"), (float)f[0], (float)f[1],
                       (float)f[2]);
    glProgramUniform3f(prog, glGetUniformLocation(prog, "u_cam_right"), (float)rt[0], (float)rt[1],
                       (float)rt[2]);
    glProgramUniform3f(prog, glGetUniformLocation(prog, "u_cam_upv"), (float)up[0], (float)up[1],
                       (float)up[2]);
    double ty = tan((cam->fov_y >= 1 && cam->fov_y <= 170 ? cam->fov_y : 60) * M_PI / 360.0);
    glProgramUniform2f(prog, glGetUniformLocation(prog, "u_tan_half"), (float)(ty * aspect),
                       (float)ty);
    glUseProgram(prog);
    glBindVertexArray(r->empty_vao);
    glDepthMask(GL_FALSE);
    glDepthFunc(GL_GEQUAL);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDepthFunc(GL_GREATER);
    glDepthMask(GL_TRUE);
    r->stats.draw_calls++;
}
