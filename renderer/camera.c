// Camera math for the 3D viewport: yaw/pitch to basis vectors, the camera-relative view
// and reversed-Z projection matrices, pixel rays and the navigation controls.
#include "renderer/camera.h"

#include <math.h>

static const double DEG = 3.14159265358979323846 / 180.0;

void camera_default(camera *c) {
    *c = (camera){.pos = {0, 0, 0}, .yaw = 0, .pitch = 0, .fov_y = 60, .near_m = 0.5};
}

static double clamp_pitch(double p) {
    if (!(p > -CAMERA_PITCH_LIMIT)) return -CAMERA_PITCH_LIMIT; // also catches NaN
    return p < CAMERA_PITCH_LIMIT ? p : CAMERA_PITCH_LIMIT;
}

static double wrap_yaw(double y) {
    if (!isfinite(y)) return 0;
    y = fmod(y, 360.0);
    if (y < 0) y += 360.0;
    return y >= 360.0 ? 0.0 : y; // -tiny + 360 rounds to 360
}

// The pitch the camera uses: stored values outside the limit still give a valid basis.
static double pitch_of(const camera *c) {
    return clamp_pitch(c->pitch);
}

void camera_forward(const camera *c, double out[3]) {
    double y = c->yaw * DEG, p = pitch_of(c) * DEG;
    out[0] = cos(p) * sin(y);
    out[1] = sin(p);
    out[2] = -cos(p) * cos(y);
}

void camera_right(const camera *c, double out[3]) {
    double y = c->yaw * DEG;
    out[0] = cos(y);
    out[1] = 0;
    out[2] = sin(y);
}

void camera_up(const camera *c, double out[3]) {
    double r[3], f[3];
    camera_right(c, r);
    camera_forward(c, f);
    out[0] = r[1] * f[2] - r[2] * f[1];
    out[1] = r[2] * f[0] - r[0] * f[2];
    out[2] = r[0] * f[1] - r[1] * f[0];
}

void camera_view_matrix(const camera *c, float m[16]) {
    double r[3], u[3], f[3];
    camera_right(c, r);
    camera_up(c, u);
    camera_forward(c, f);
    // Rows: right, up, -forward (view space looks down -Z). Column-major storage.
    for (int i = 0; i < 3; i++) {
        m[i * 4 + 0] = (float)r[i];
        m[i * 4 + 1] = (float)u[i];
        m[i * 4 + 2] = (float)-f[i];
        m[i * 4 + 3] = 0.0f;
    }
    m[12] = m[13] = m[14] = 0.0f;
    m[15] = 1.0f;
}

static double fov_of(const camera *c) {
    double f = c->fov_y;
    if (!(f >= 1.0)) return 1.0;
    return f <= 170.0 ? f : 170.0;
}

static double near_of(const camera *c) {
    return c->near_m > 0 ? c->near_m : 0.5;
}

static double aspect_ok(double aspect) {
    return aspect > 0 && isfinite(aspect) ? aspect : 1.0;
}

void camera_projection_matrix(const camera *c, double aspect, float m[16]) {
    double f = 1.0 / tan(0.5 * fov_of(c) * DEG);
    for (int i = 0; i < 16; i++)
        m[i] = 0.0f;
    m[0] = (float)(f / aspect_ok(aspect));
    m[5] = (float)f;
    m[11] = -1.0f;             // w_clip = -z_view
    m[14] = (float)near_of(c); // z_clip = near, so depth = near / -z_view
}

void camera_view_projection(const camera *c, double aspect, float m[16]) {
    double r[3], u[3], f[3];
    camera_right(c, r);
    camera_up(c, u);
    camera_forward(c, f);
    camera_basis_view_projection(c, r, u, f, aspect, m);
}

void camera_basis_view_projection(const camera *c, const double right[3], const double up[3],
                                  const double forward[3], double aspect, float m[16]) {
    float p[16], v[16];
    camera_projection_matrix(c, aspect, p);
    // Rows: right, up, -forward (view space looks down -Z). Column-major storage.
    for (int i = 0; i < 3; i++) {
        v[i * 4 + 0] = (float)right[i];
        v[i * 4 + 1] = (float)up[i];
        v[i * 4 + 2] = (float)-forward[i];
        v[i * 4 + 3] = 0.0f;
    }
    v[12] = v[13] = v[14] = 0.0f;
    v[15] = 1.0f;
    for (int col = 0; col < 4; col++)
        for (int row = 0; row < 4; row++) {
            double s = 0;
            for (int k = 0; k < 4; k++)
                s += (double)p[k * 4 + row] * v[col * 4 + k];
            m[col * 4 + row] = (float)s;
        }
}

void camera_ray(const camera *c, double aspect, double sx, double sy, double dir[3]) {
    double r[3], u[3], f[3];
    camera_right(c, r);
    camera_up(c, u);
    camera_forward(c, f);
    camera_basis_ray(c, r, u, f, aspect, sx, sy, dir);
}

void camera_basis_ray(const camera *c, const double r[3], const double u[3], const double f[3],
                      double aspect, double sx, double sy, double dir[3]) {
    double t = tan(0.5 * fov_of(c) * DEG);
    double vx = (2.0 * sx - 1.0) * t * aspect_ok(aspect);
    double vy = (1.0 - 2.0 * sy) * t; // sy grows downward
    double len = 0;
    for (int i = 0; i < 3; i++) {
        dir[i] = r[i] * vx + u[i] * vy + f[i];
        len += dir[i] * dir[i];
    }
    len = sqrt(len);
    for (int i = 0; i < 3; i++)
        dir[i] /= len;
}

void camera_look(camera *c, double dyaw, double dpitch) {
    c->yaw = wrap_yaw(c->yaw + dyaw);
    c->pitch = clamp_pitch(c->pitch + dpitch);
}

void camera_move_local(camera *c, double forward, double right, double up) {
    double f[3], r[3];
    camera_forward(c, f);
    camera_right(c, r);
    for (int i = 0; i < 3; i++)
        c->pos[i] += f[i] * forward + r[i] * right;
    c->pos[1] += up;
}

// Yaw and pitch that look along d (not necessarily unit). A vertical d keeps the
// current yaw, which is otherwise undefined.
static void look_along(camera *c, const double d[3]) {
    double h = sqrt(d[0] * d[0] + d[2] * d[2]);
    if (h > 1e-12 * fabs(d[1])) c->yaw = wrap_yaw(atan2(d[0], -d[2]) / DEG);
    c->pitch = clamp_pitch(atan2(d[1], h) / DEG);
}

void camera_orbit(camera *c, const double pivot[3], double dyaw, double dpitch) {
    double to[3] = {pivot[0] - c->pos[0], pivot[1] - c->pos[1], pivot[2] - c->pos[2]};
    double dist = sqrt(to[0] * to[0] + to[1] * to[1] + to[2] * to[2]);
    if (dist > 0) look_along(c, to);
    camera_look(c, dyaw, dpitch);
    camera_focus(c, pivot, dist);
}

void camera_dolly(camera *c, const double pivot[3], double factor) {
    if (!(factor > 0) || !isfinite(factor)) return;
    double off[3] = {c->pos[0] - pivot[0], c->pos[1] - pivot[1], c->pos[2] - pivot[2]};
    double dist = sqrt(off[0] * off[0] + off[1] * off[1] + off[2] * off[2]);
    if (dist <= 0) return; // no direction to move along
    double want = dist * factor, lim = 2.0 * near_of(c);
    // Stop at 2 * near, but never push a camera that is already closer away.
    if (want < lim) want = fmin(fmax(dist, want), lim);
    for (int i = 0; i < 3; i++)
        c->pos[i] = pivot[i] + off[i] * (want / dist);
}

void camera_focus(camera *c, const double point[3], double distance) {
    double f[3];
    camera_forward(c, f);
    for (int i = 0; i < 3; i++)
        c->pos[i] = point[i] - f[i] * distance;
}
