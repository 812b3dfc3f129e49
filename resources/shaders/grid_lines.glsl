// Lines about a pixel wide where k crosses an integer, faded where they would crowd
// (the debug overlays' tile and level grids).
float grid_lines(vec2 k) {
    vec2 fw = max(fwidth(k), vec2(1e-5));
    vec2 d = abs(fract(k + 0.5) - 0.5) / fw;
    return (1.0 - smoothstep(0.0, 1.5, min(d.x, d.y))) * (1.0 - smoothstep(0.12, 0.3, max(fw.x, fw.y)));
}
