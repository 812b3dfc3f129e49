// Erosion kernels on a plain row-major float array: thermal (angle of repose) and
// particle-based hydraulic erosion (droplets, after H. T. Beyer 2015). The brush
// engine gathers its footprint plus a halo into an erosion_grid, with a per-cell
// weight (falloff x strength x pressure), runs a kernel and writes back the cells
// whose weight is > 0.
//
// Shared contract:
//  - A cell whose weight is 0 never changes, to the bit (the hydraulic kernel may store
//    its own bits back); it may be read. Negative or NaN weights count as 0, weights
//    above 1 as 1.
//  - Deterministic: the output depends only on the inputs (no global state); the
//    hydraulic kernel draws from its own PRNG seeded by `seed` and runs its droplets
//    in bands of columns on the editing pool's threads (editor/edit/parallel.h, so
//    call it from the editor's thread), bands that cannot touch a common cell at the
//    same time: the same heights on any number of threads.
//  - Finite heights in (|h| <= 1e9 m, not checked), finite heights out. Invalid grids
//    or parameters (see the validate functions) leave the grid untouched, as does
//    running out of memory.
//  - Heights enter the physics only as slopes (height / spacing): a grid and a copy
//    scaled by a power of two in all three axes give the same result, scaled.
//  - Memory per call: thermal copies the weighted bounding box (8 bytes a cell);
//    hydraulic builds a spawn table and clamped weights (20 bytes a cell of the grid).
#ifndef OROGEN_EDITOR_EROSION_H
#define OROGEN_EDITOR_EROSION_H

#include "io/err.h"

#include <stdint.h>

// Row-major grid of heights in metres; cell (i, j) is heights[j * width + i]; cells
// are `spacing` metres apart.
typedef struct erosion_grid {
    float *heights;
    const float *weight; // same layout; in [0, 1]; 0 = read-only halo
    int width, height;   // >= 1 each, width * height <= 2^31 - 1
    float spacing;       // metres, [1e-4, 1e7]
    // NULL, or where the kernel reports how far it is; once that is cancelled the
    // kernel stops early and the grid holds a partial result for the caller to discard.
    struct og_progress *progress;
} erosion_grid;

// 0, or -1 with a message naming the bad field.
int erosion_grid_validate(const erosion_grid *g, og_error *err);

// --- Thermal erosion ---------------------------------------------------------------
// Material slides from a cell to its lower 8-neighbours wherever the drop exceeds
// tan(talus) x distance (diagonals are sqrt(2) x spacing away), split in proportion
// to each neighbour's excess. Each iteration reads the heights of the previous one,
// so the result does not depend on scan order. A transfer between two cells is
// scaled by the smaller of their weights and never involves a zero-weight cell, so
// mass is conserved up to float rounding.
//
// Tolerances (tested): on a grid weighted 1 inside a zero halo, after enough
// iterations at rate 1 (or 0.5) no slope between two weighted neighbours exceeds
// tan(talus) + 1e-4 (the float step of the heights over the spacing: heights of a few
// hundred metres at 2 m spacing; about 130 iterations suffice there at rate 1), and
// the height sum changes by at most 1e-5 relative (measured: about 1e-8).
typedef struct thermal_params {
    float talus_deg; // angle of repose in degrees, (0, 89]
    int iterations;  // [0, 1000000]; 0 does nothing
    float rate;      // (0, 1]; 1 moves half the largest excess drop of each cell
} thermal_params;

int erosion_thermal_validate(const thermal_params *p, og_error *err);
void erosion_thermal(erosion_grid *g, const thermal_params *p);

// --- Hydraulic erosion -------------------------------------------------------------
// Droplets start at random points of the bilinear cells whose four corners are
// weighted, with density proportional to the cells' mean weight (so scaling all
// weights alike changes how much happens, not where). Each step a droplet turns
// towards the downhill bilinear gradient (keeping `inertia` of its direction), moves
// one cell, and compares its sediment with its capacity
//     max(-dh x speed x water x capacity, min_capacity x spacing)   (metres)
// where dh is the height change of the step: below capacity it erodes
// erosion x (capacity - sediment), at most -dh, over a disc of radius_cells; above
// it it deposits deposition x (sediment - capacity), and going uphill up to dh of
// its sediment, into the four corners of its cell. Then
// speed^2 -= gravity x dh / spacing and water *= 1 - evaporation. Every change at
// a cell is multiplied by the cell's weight, and erosion never lowers a cell below
// the height the droplet flows to, so no pits are dug. A droplet whose next point's
// cell has a zero-weight corner or leaves the grid, or that reaches max_lifetime,
// dies and lays all the sediment it carries over the disc around where it is
// (weighted cells only).
//
// Mass: every change is booked as the float difference actually stored, and what a
// final drop cannot place for rounding is carried to the next one, so a call changes
// the height sum by at most half a float step of one height (plus double rounding).
// Tested: |sum after - sum before| <= 1e-4 x sum over cells of |change|, and
// <= 1e-9 x that + one float step of the highest cell (measured: about 1e-11).
typedef struct hydraulic_params {
    uint64_t seed;
    int droplets;        // [0, 100000000]
    int max_lifetime;    // steps of one cell, [1, 10000]
    float inertia;       // [0, 1]; how much of its direction a droplet keeps per step
    float capacity;      // [0, 1000]
    float min_capacity;  // [0, 1000]; in units of spacing
    float erosion;       // [0, 1]
    float deposition;    // [0, 1]
    float evaporation;   // [0, 1]
    float gravity;       // [0, 1000]
    float radius_cells;  // (0, 32]; radius of the erosion disc in cells
    float initial_water; // (0, 1000]
    float initial_speed; // [0, 1000]; cells per step (the step itself is always one cell)
} hydraulic_params;

// Height sums in m x cells (each cell's change added up), all >= 0.
// eroded ~= deposited + dropped, to the mass tolerance above.
typedef struct hydraulic_report {
    double eroded;    // material removed
    double deposited; // material laid down while droplets flowed
    double dropped;   // sediment still carried when droplets died, laid down where they died
    int droplets;     // droplets started (0 when no cell can take one)
    int64_t steps;    // steps the droplets took, in all
} hydraulic_report;

void hydraulic_params_default(hydraulic_params *p);
int erosion_hydraulic_validate(const hydraulic_params *p, og_error *err);
// report may be NULL.
void erosion_hydraulic(erosion_grid *g, const hydraulic_params *p, hydraulic_report *report);

#endif
