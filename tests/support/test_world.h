// Helpers shared by the unit tests that build a small world in memory: the same
// generated flat terrain, a quiet warning sink and a seeded random sequence, so stacks
// of layers are compared against plain arrays on identical ground.
#ifndef OROGEN_TEST_WORLD_H
#define OROGEN_TEST_WORLD_H

#include "editor/params/world_grid.h"
#include "editor/world/world.h"

#include <stdint.h>

// A world's warning sink that drops every message.
void test_silent(void *user, const char *message);
// A flat fBm world of size samples per side (0: unbounded), 1 m spacing, 300 m high.
world_params test_flat_fbm_params(int64_t size);
// The world for p with a 256 MB cache and 2 workers (fails the test if it cannot open).
world *test_world_open(const world_params *p);
// Samples of one slot of the coarse heights (the base, a layer) over r, malloc'd
// (fails the test if they cannot be read).
float *test_read_slot(world *w, int32_t slot, grid_rect r);
// xorshift64: the next number of the sequence in *state (never 0 if seeded non-zero).
uint64_t test_rng_next(uint64_t *state);
// A number in [0, 1) from the sequence.
double test_rng_unit(uint64_t *state);

#endif
