// A planet's ground curvature for the material rules (planet_rules.glsl) and the mask
// overlay; planet.frag includes it after its normal texture's uniforms and metre_axes.
// The rules' curvature, -100 x the Laplacian (positive convex), from the normal texture:
// the divergence of the gradient its neighbouring texels give. Each gradient component is
// signed along the direction the metres grow on the screen (metre_axes), as the faces'
// tangent frames differ in handedness. Coarser chunks' textures see broader shapes.
float curvature_here(vec3 up) {
    vec3 t = normalize(u_face_axis - up * dot(up, u_face_axis)), b = cross(up, t), ta, ba;
    metre_axes(up, ta, ba);
    vec2 sgn = vec2(dot(t, ta) < 0.0 ? -1.0 : 1.0, dot(b, ba) < 0.0 ? -1.0 : 1.0);
    vec2 size = vec2(textureSize(u_normals, 0).xy);
    vec2 st = (v_metres - u_normal_map.xy) * u_normal_map.z / size;
    float lap = 0.0;
    for (int k = 0; k < 2; k++) {
        vec2 d = (k == 0 ? vec2(1.0, 0.0) : vec2(0.0, 1.0)) / size;
        vec2 a = texture(u_normals, vec3(st + d, u_normal_map.w)).rg;
        vec2 c = texture(u_normals, vec3(st - d, u_normal_map.w)).rg;
        float ga = -a[k] / sqrt(max(1.0 - dot(a, a), 1e-4)), gc = -c[k] / sqrt(max(1.0 - dot(c, c), 1e-4));
        lap += sgn[k] * (ga - gc) * 0.5 * u_normal_map.z; // a texel is 1 / z metres
    }
    return -100.0 * lap;
}
