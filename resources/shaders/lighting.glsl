// Sun, sky and fog, shared by the sky, terrain and water shaders so that distant
// terrain fades into exactly the sky behind it.
uniform vec3 u_sun_dir;      // unit, toward the sun
uniform vec3 u_sun_colour;
uniform vec3 u_sky_zenith;
uniform vec3 u_sky_horizon;
uniform float u_fog_density; // per metre (exponential fog)

vec3 sky_colour(vec3 dir) {
    float up = clamp(dir.y, -1.0, 1.0);
    vec3 sky = mix(u_sky_horizon, u_sky_zenith, pow(max(up, 0.0), 0.45));
    vec3 ground = u_sky_horizon * 0.75;
    sky = up < 0.0 ? mix(u_sky_horizon, ground, clamp(-up * 4.0, 0.0, 1.0)) : sky;
    float sun = max(dot(dir, u_sun_dir), 0.0);
    sky += u_sun_colour * (pow(sun, 600.0) * 4.0 + pow(sun, 8.0) * 0.15);
    return sky;
}

// Exponential fog toward the sky colour seen along the same direction.
vec3 apply_fog(vec3 colour, vec3 rel) {
    float dist = length(rel);
    float f = 1.0 - exp(-u_fog_density * dist);
    vec3 dir = rel / max(dist, 1e-6);
    return mix(colour, sky_colour(vec3(dir.x, max(dir.y, 0.0) * 0.3, dir.z)), f);
}

vec3 sunlit(vec3 albedo, vec3 n, vec3 view_dir, float shininess, float spec) {
    float diffuse = max(dot(n, u_sun_dir), 0.0);
    vec3 ambient = mix(u_sky_horizon * 0.35, u_sky_zenith * 0.55, n.y * 0.5 + 0.5);
    vec3 h = normalize(u_sun_dir + view_dir);
    float s = pow(max(dot(n, h), 0.0), shininess) * spec * step(0.0, diffuse);
    return albedo * (ambient + u_sun_colour * diffuse) + u_sun_colour * s;
}
