// Optional libraries (OpenImageIO, GDAL) live in modules opened with dlopen on first
// use, so that starting orogen does not load hundreds of shared libraries it may
// never need. This finds and opens one.
#ifndef OROGEN_IO_MODULE_LOAD_H
#define OROGEN_IO_MODULE_LOAD_H

#include <stddef.h>

// Opens the module file_name (e.g. "liborogen_gdal.so") from $env_var, then the
// installed lib/orogen beside bin/, then build_path (the build tree; may be NULL).
// Returns the dlopen handle, or NULL with why saying what failed.
void *module_open(const char *env_var, const char *file_name, const char *build_path, char *why,
                  size_t why_len);

#endif
