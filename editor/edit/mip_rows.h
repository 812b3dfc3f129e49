// The flat world's mip filter (edit_mips.c) split into its two passes: each child row
// filtered across once, then three filtered rows combined down per parent row. The
// same float operations in the same order as the 3 x 3 filter per parent, so the same
// bits; a child row filtered once serves the two parent rows that read it.
#ifndef OROGEN_EDITOR_MIP_ROWS_H
#define OROGEN_EDITOR_MIP_ROWS_H

// Parent rows 0 .. ph - 1 (pw samples each, rows `stride` apart in dst and before) from
// the child window win (2 ph + 1 rows of cw >= 2 pw + 1 values, pw <= TILE_SIZE; parent x reads
// children 2x .. 2x + 2): dst = before + (0.25 a + 0.5 b + 0.25 g) down the rows a, b, g filtered
// across as 0.25 c[2x] + 0.5 c[2x + 1] + 0.25 c[2x + 2]. before NULL: dst's own values.
// One call a block, not three a row: a stroke's moves update many short rows.
void mip_rows_block(const float *win, int cw, int pw, int ph, const float *before, float *dst,
                    int stride);

#endif
