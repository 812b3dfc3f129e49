// A world made from a raster (`new flat from=FILE`) in a batch script imports its parts as
// they are needed: a shard of a tiled export (`export ... tiles=CxR shard=I/N`) composites
// and writes only the tiles its part of the region reads, so N shards split the import as
// they split the export. Any other command first imports the rest (base_pending_finish),
// so it sees the whole raster, exactly as an import of the whole would have made it: the
// import is a copy per sample, and the mip levels of the parts agree with those of the
// whole once the parts are all in.
#ifndef OROGEN_EDITOR_CMD_BASE_PENDING_H
#define OROGEN_EDITOR_CMD_BASE_PENDING_H

#include "editor/cmd/context.h"
#include "editor/interchange/import.h"

typedef struct base_pending base_pending;

// Takes src (freed with the pending import) for world w; o as place_base set it up
// (position, starting state). journal_paused: the journal names the raster instead of
// holding its samples. NULL on no memory (src is then still the caller's).
base_pending *base_pending_new(world *w, const char *path, import_source *src,
                               const import_options *o, int journal_paused);
// Imports the world tiles of r (level-0 coarse samples) not imported yet.
int base_pending_require(base_pending *b, grid_rect r, og_error *err);
// The lowest and highest heights of level-0 samples r (clipped to the world) as the
// import makes them: its samples, copied. 0 when r holds none.
int base_pending_range(const base_pending *b, grid_rect r, double *lo, double *hi);
// Imports everything not imported yet.
int base_pending_finish(base_pending *b, og_error *err);
void base_pending_free(base_pending *b);

// The context's pending import: finished (the whole world imported) and forgotten; or
// forgotten with its world (a new world replaces it, the process ends).
int cmd_base_settle(cmd_context *ctx, og_error *err);
void cmd_base_drop(cmd_context *ctx);

#endif
