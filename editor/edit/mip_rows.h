// The flat world's mip filter (edit_mips.c) split into its two passes: each child row
// filtered across once, then three filtered rows combined down per parent row. The
// same float operations in the same order as the 3 x 3 filter per parent, so the same
// bits; a child row filtered once serves the two parent rows that read it.
#ifndef OROGEN_EDITOR_MIP_ROWS_H
#define OROGEN_EDITOR_MIP_ROWS_H

// out[x] = 0.25 c[2x] + 0.5 c[2x+1] + 0.25 c[2x+2], x < n (c holds 2n + 1 values).
void mip_rows_across(const float *c, int n, float *out);

// dst[x] = before[x] + (0.25 a[x] + 0.5 b[x] + 0.25 g[x]); before may be dst.
void mip_rows_down(const float *a, const float *b, const float *g, const float *before, float *dst,
                   int n);

#endif
