// Writes one-channel 32-bit float OpenEXR files ourselves rather than through
// OpenImageIO: scanline, ZIP compression (blocks of 16 rows, OpenEXR's byte split and
// delta predictor, deflate at OpenEXR's default level 4) with libdeflate instead of
// zlib, the blocks compressed on every core this process may run on. Same format and
// level as OpenEXR's own writer, about twice as fast per core; the bytes depend only
// on the samples (no time stamps, no thread-count effect).
#ifndef OROGEN_IO_EXR_WRITE_H
#define OROGEN_IO_EXR_WRITE_H

#include "io/err.h"

// Rows per ZIP block (OpenEXR's ZIP_COMPRESSION).
#define EXR_ZIP_BLOCK_ROWS 16

// Writes width x height samples (row 0 first) as channel `channel` of path,
// atomically: temp file beside it, fsync, rename, with the umask's mode. Sizes 1..65536
// per side; channel is 1..255 characters.
int exr_write_float(const char *path, const float *samples, int width, int height,
                    const char *channel, og_error *err);

#endif
