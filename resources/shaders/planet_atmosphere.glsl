// A planet's sky: Rayleigh single scattering through an exponential atmosphere (scale
// height u_scale_height, thickness u_atm_top), integrated along the view ray in a few
// steps. Distances are from the camera; altitudes are computed from the camera's own
// precise altitude so nothing cancels at Earth's radius in single precision.
uniform float u_radius;       // metres from the centre to the datum
uniform float u_scale_height; // metres
uniform float u_atm_top;      // metres above the datum where the air ends
uniform vec3 u_beta;          // scattering per metre at the datum (RGB)
uniform float u_cam_r;        // the camera's distance from the centre
uniform float u_cam_alt;      // and its altitude above the datum (precise)
uniform vec3 u_cam_up;        // the local vertical at the camera
uniform vec3 u_sun_dir;
uniform vec3 u_sun_colour;

const int ATM_STEPS = 8;

// |camera + t dir|^2 - R^2, mu = dot(dir, up).
float above_datum_sq(float t, float mu) {
    return u_cam_alt * (2.0 * u_radius + u_cam_alt) + t * t + 2.0 * u_cam_r * t * mu;
}

float altitude_at(float t, float mu) {
    float q = above_datum_sq(t, mu);
    return q / (sqrt(max(q + u_radius * u_radius, 0.0)) + u_radius);
}

// Where the ray is inside the air: [t0, t1]; false when it never is.
bool air_span(float mu, out float t0, out float t1) {
    float top = u_radius + u_atm_top;
    float rm = u_cam_r * mu;
    float c = (u_cam_alt - u_atm_top) * (u_cam_r + top); // r^2 - top^2
    float disc = rm * rm - c;
    if (disc < 0.0) return false;
    float q = sqrt(disc);
    t0 = max(-rm - q, 0.0);
    t1 = -rm + q;
    return t1 > 0.0;
}

// Where the ray first meets the sphere h metres above the datum (the ground seen at a
// fragment, free of the sag of the triangle's chords, which the haze would show quad by
// quad from afar); fallback when it never does. The stable root: no cancellation a
// few metres above the ground.
float ray_to_height(vec3 dir, float h, float fallback) {
    float mu = dot(dir, u_cam_up), rm = u_cam_r * mu;
    float c = (u_cam_alt - h) * (2.0 * u_radius + u_cam_alt + h); // |cam|^2 - (R + h)^2
    float disc = rm * rm - c;
    if (disc < 0.0) return fallback;
    float q = sqrt(disc);
    if (c > 0.0) return rm < 0.0 ? c / (q - rm) : fallback; // outside: the near root
    return q - rm;                                          // inside: the far one
}

// In-scattered light along the ray up to t_end, and what of the light behind is left.
vec3 atmosphere(vec3 dir, float t_end, out vec3 transmittance) {
    transmittance = vec3(1.0);
    float mu = dot(dir, u_cam_up), t0, t1;
    if (!air_span(mu, t0, t1)) return vec3(0.0);
    t1 = min(t1, t_end);
    if (t1 <= t0) return vec3(0.0);
    float ds = (t1 - t0) / float(ATM_STEPS);
    vec3 inscatter = vec3(0.0);
    float optical = 0.0;
    for (int i = 0; i < ATM_STEPS; i++) {
        float t = t0 + (float(i) + 0.5) * ds;
        float h = max(altitude_at(t, mu), 0.0);
        float rho = exp(-h / u_scale_height);
        optical += rho * ds * 0.5;
        vec3 up = normalize(u_cam_up * u_cam_r + dir * t);
        float mu_s = dot(up, u_sun_dir);
        // Light reaching the sample: Chapman-like path through the air above it, none
        // once the planet is in the way.
        float sun_path = rho * u_scale_height / max(mu_s + 0.15, 0.03);
        float lit = smoothstep(-0.08, 0.02, mu_s);
        inscatter += rho * ds * exp(-u_beta * (optical + sun_path)) * lit;
        optical += rho * ds * 0.5;
    }
    transmittance = exp(-u_beta * optical);
    float c = dot(dir, u_sun_dir);
    float phase = 0.0596831 * (1.0 + c * c); // 3 / (16 pi) (1 + cos^2)
    return inscatter * u_beta * phase * u_sun_colour * 14.0;
}
