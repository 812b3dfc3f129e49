// Erosion kernels on a plain row-major float array: thermal (angle of repose) and
// particle-based hydraulic erosion (droplets, after H. T. Beyer 2015). The brush
// engine gathers its footprint plus a halo into an erosion_grid, with a per-cell
// weight (falloff x strength x pressure), runs a kernel and writes back the cells
// whose weight is > 0.
//
// Shared contract:
//  - A cell whose weight is 0 is never written (its bits stay the same); it may be
//    read. Negative or NaN weights count as 0 and weights above 1 as 1.
//  - Deterministic: the output depends only on the inputs (no threads, no global
//    state); the hydraulic kernel draws from its own PRNG seeded by `seed`.
//  - Finite heights in (|h| <= 1e9 m, not checked), finite heights out. Invalid grids
//    or parameters (see the validate functions) leave the grid untouched, as does
//    running out of memory.
//  - Heights enter the physics only as slopes (height / spacing), so a grid and a
//    copy scaled uniformly in all three axes erode alike.
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
// Droplets start at random points of the weighted area (density proportional to the
// weight, so scaling all weights alike changes how much, not where), follow the
// bilinear gradient with inertia, erode over a disc of radius_cells while they carry
// less sediment than their capacity and deposit when they carry more, slow down
// uphill and evaporate. Every change at a cell is multiplied by its weight; an
// erosion never lowers a cell below the height the droplet flows to next, so no
// pits are dug. A droplet that would step onto a cell touching a zero weight or
// the grid's edge, or that reaches max_lifetime, dies and lays all the sediment it
// still carries over the disc around where it is (weighted cells only).
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
    float capacity;      // [0, 1000]; sediment capacity per unit slope x speed x water
    float min_capacity;  // [0, 1000]; floor of the capacity, in cell heights (x spacing m)
    float erosion;       // [0, 1]; fraction of the free capacity eroded per step
    float deposition;    // [0, 1]; fraction of the surplus sediment deposited per step
    float evaporation;   // [0, 1]; fraction of the water lost per step
    float gravity;       // [0, 1000]; speed^2 gained per unit of slope descended
    float radius_cells;  // (0, 32]; radius of the erosion disc in cells
    float initial_water; // (0, 1000]
    float initial_speed; // [0, 1000]
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
