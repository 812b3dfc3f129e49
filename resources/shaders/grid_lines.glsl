// Lines about a pixel wide where k crosses an integer, faded where they would crowd
// (the debug overlays' tile and level grids).
// fw: how much k changes from a pixel to the next (fwidth).
float grid_lines_across(vec2 k, vec2 fw) {
    fw = max(fw, vec2(1e-5));
    vec2 d = abs(fract(k + 0.5) - 0.5) / fw;
    return (1.0 - smoothstep(0.0, 1.5, min(d.x, d.y))) * (1.0 - smoothstep(0.12, 0.3, max(fw.x, fw.y)));
}

float grid_lines(vec2 k) {
    return grid_lines_across(k, fwidth(k));
}
