// What the viewport shows and how: the view mode, the render settings the `render`
// and `view` commands change, and the brush cursor drawn on the terrain.
#ifndef OROGEN_RENDERER_RENDER_SETTINGS_H
#define OROGEN_RENDERER_RENDER_SETTINGS_H

#define RENDER_MIN_LEVELS 3
#define RENDER_MAX_LEVELS 12
#define BRUSH_FALLOFF_SAMPLES 64

typedef enum view_mode {
    VIEW_SHADED = 0,
    VIEW_WIREFRAME = 1,
    VIEW_LEVELS = 2, // clipmap level colours
    VIEW_HEIGHT = 3,
    VIEW_SLOPE = 4,
    VIEW_MODE_COUNT
} view_mode;

const char *view_mode_name(view_mode m);
int view_mode_parse(const char *text); // -1 if unknown

typedef struct render_settings {
    int levels;             // clipmap levels, RENDER_MIN_LEVELS .. RENDER_MAX_LEVELS (8)
    int parallax;           // parallax-mapped detail near the camera (1)
    int parallax_steps;     // parallax iterations: the quality setting, 1 .. 32 (8)
    double detail_distance; // metres: the detail fades out by this distance (150)
    view_mode view;
    double sun_yaw, sun_pitch; // degrees (135, 35)
    double fog_density;        // per metre (0: automatic from the clipmap's reach)
    int culling;               // per-block frustum culling; planets: also occlusion by nearer
                               // ground (1)
    int morph;                 // transition morphing between levels (1)
    double contours;           // metres between contour lines drawn over the terrain; 0: none
    double sun_rotation;       // degrees a second the editor window turns the sun (0: still)
    int tile_grid;             // lines along the edges of the world's tiles (0)
    int level_grid;            // each clipmap level's vertex grid in its level's colour (0)
    int auto_materials;        // the automatic material rules (grass, rock, snow by height and
                               // slope) colour unpainted ground; off: a neutral clay (1)
    double lod_pixels;         // planets: pixels a sample may cover before its chunk splits (6)
    double refine_pixels;      // flat worlds: pixels of geometric error (projected) at which a
                               // part of a coarse clipmap level starts to be drawn at twice
                               // its density, fully at 1.5x that (renderer/clip_refine.h);
                               // 0: never (0)
    double skyline_pixels;     // flat worlds, while refine_pixels is 0: the same, for the
                               // parts near the skyline only (renderer/clip_skyline.h) (0)
    int antialias;             // edges smoothed in the finished image (renderer/antialias.h) (1)
    // A layer mask being edited, drawn over the terrain (the Layers panel's mask editor):
    // mask_terms bits 1 height, 2 slope, 4 curvature, 8 flow (0: none drawn), each term's corners
    // where its weight starts rising, reaches 1, starts falling, reaches 0 (metres,
    // degrees, -100 x Laplacian; +-1e30 for open ends), mask_invert as the mask's invert.
    int mask_terms, mask_invert;
    float mask_height[4], mask_slope[4], mask_curvature[4];
    // Flat worlds: the flow term (mask_terms bit 8) over a field of upstream areas (m2)
    // the app read around the view, w x h samples `spacing` metres apart from (x0, z0),
    // row-major, not owned; serial changes when the field does. Where it has no field
    // the flow term is not drawn.
    float mask_flow[4];
    const float *mask_flow_area;
    int mask_flow_w, mask_flow_h;
    double mask_flow_x0, mask_flow_z0, mask_flow_spacing;
    unsigned mask_flow_serial;
} render_settings;

void render_settings_default(render_settings *s);
// Whether the finished image gets its edges smoothed: antialias on, in the shaded view
// (the debug views show their lines and colours pixel for pixel).
int render_settings_smooth_edges(const render_settings *s);

typedef struct brush_cursor {
    int visible;
    double x, z;                          // world metres
    double radius;                        // metres
    float falloff[BRUSH_FALLOFF_SAMPLES]; // weight at distance i/(N-1) of the radius
    float color[3]; // the tool's colour (0-1 RGB); with opacity 0 the default orange
    float opacity;  // how strongly the falloff is tinted at the centre (follows strength)
    // A volume tool's brush: a sphere of the radius around (x, y, z) instead of the disc
    // draped on the ground.
    int sphere;
    double y;
} brush_cursor;

#endif
