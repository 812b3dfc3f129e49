// The commonest heightmap, a greyscale PNG of 8 or 16 bits, read without OpenImageIO:
// loading OIIO's ~260 libraries costs a process ~0.25 s, and libdeflate inflates the
// image data in one call about twice as fast as zlib under libpng. This reader takes
// only files it reads exactly as OpenImageIO does (greyscale, 8 or 16 bits, not
// interlaced, no sBIT or tRNS, every CRC and the zlib checksum right, the image data
// exactly the image's size); anything else it leaves to OpenImageIO, which then gives
// the values or the error message it always gave.
#ifndef OROGEN_IO_PNG_GRAY_H
#define OROGEN_IO_PNG_GRAY_H

// 1: read, *samples malloc'd (width x height, rows from the top, values as stored:
// 16-bit 40000 reads as 40000.0), *bits 8 or 16. 0: not a file this reader takes
// (nothing allocated; read it through OpenImageIO). Sides up to max_size.
int png_gray_read(const char *path, int max_size, float **samples, int *width, int *height,
                  int *bits);

#endif
