// The debug views' colour ramp (height and slope colours), shared with the benchmark's
// full-resolution reference renderer.
vec3 ramp(float t) { // blue, green, yellow, red, white
    t = clamp(t, 0.0, 1.0);
    vec3 c0 = vec3(0.1, 0.2, 0.7), c1 = vec3(0.1, 0.65, 0.25), c2 = vec3(0.95, 0.85, 0.2);
    vec3 c3 = vec3(0.85, 0.25, 0.1), c4 = vec3(1.0);
    return t < 0.25 ? mix(c0, c1, t * 4.0) : t < 0.5 ? mix(c1, c2, t * 4.0 - 1.0)
         : t < 0.75 ? mix(c2, c3, t * 4.0 - 2.0) : mix(c3, c4, t * 4.0 - 3.0);
}
