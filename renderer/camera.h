// The 3D viewport's camera: position (double, metres) and yaw/pitch, the matrices the
// renderer uploads, pixel rays for picking, and the fly/orbit/dolly/focus controls.
// Conventions: X east, Y up, Z south; yaw 0 looks toward -Z, 90 toward +X; pitch > 0
// looks up. Matrices are column-major float[16] and camera-relative (the view matrix
// has no translation): the renderer subtracts pos in double before converting vertices
// to float, so nothing jitters far from the origin.
#ifndef OROGEN_RENDERER_CAMERA_H
#define OROGEN_RENDERER_CAMERA_H

#define CAMERA_PITCH_LIMIT 89.9

typedef struct camera {
    double pos[3];     // metres
    double yaw, pitch; // degrees
    double fov_y;      // vertical field of view, degrees (1..170)
    double near_m;     // near plane distance, metres (> 0)
} camera;

// pos 0,0,0, yaw 0, pitch 0, fov 60, near 0.5.
void camera_default(camera *c);

void camera_forward(const camera *c, double out[3]); // unit view direction
void camera_right(const camera *c, double out[3]);   // unit, horizontal
void camera_up(const camera *c, double out[3]);      // unit, = right x forward

// Rotation only (the camera sits at the origin of the space the matrix applies to).
void camera_view_matrix(const camera *c, float m[16]);
// Reversed-Z, infinite far plane, for glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE) with
// depth cleared to 0 and GL_GREATER: depth = near / -z_view (1 at near, 0 at infinity).
void camera_projection_matrix(const camera *c, double aspect, float m[16]);
// proj * view.
void camera_view_projection(const camera *c, double aspect, float m[16]);

// Ray through a pixel: sx, sy in [0,1] from the top-left corner of the image (0.5, 0.5 =
// centre). dir is unit, world space; the ray starts at c->pos.
void camera_ray(const camera *c, double aspect, double sx, double sy, double dir[3]);

// The same two from any unit basis (a planet's camera turns in its local frame).
void camera_basis_view_projection(const camera *c, const double right[3], const double up[3],
                                  const double forward[3], double aspect, float m[16]);
void camera_basis_ray(const camera *c, const double right[3], const double up[3],
                      const double forward[3], double aspect, double sx, double sy, double dir[3]);

// Controls. All keep pitch within +-CAMERA_PITCH_LIMIT and yaw in [0, 360).
// Fly mode mouse look.
void camera_look(camera *c, double dyaw, double dpitch);
// Fly: metres along forward, right and world up.
void camera_move_local(camera *c, double forward, double right, double up);
// Rotates around pivot keeping the distance; afterwards the camera looks at pivot.
// dyaw/dpitch turn the view as camera_look does: the camera first turns to face pivot,
// then its yaw/pitch change, then it backs off to the same distance (positive dpitch
// raises the view, so the camera sinks below the pivot).
void camera_orbit(camera *c, const double pivot[3], double dyaw, double dpitch);
// Moves toward pivot along the pivot-camera line: new distance = old * factor (factor > 0,
// otherwise nothing happens); never closer than 2 * near (a camera already closer stays).
void camera_dolly(camera *c, const double pivot[3], double factor);
// Keeps yaw/pitch and places the camera `distance` back along its view direction so
// that it looks at point.
void camera_focus(camera *c, const double point[3], double distance);

#endif
