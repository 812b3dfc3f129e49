// libFuzzer target: the stamp image reader (OpenImageIO through the image module:
// PNG, TIFF, EXR, PGM, PFM; colour to luminance). The first byte picks the format.
#include "editor/tools/stamp.h"
#include "fuzz_support.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    if (size < 1) return 0;
    static const char *const names[] = {"s.png", "s.tif", "s.exr", "s.pgm", "s.pfm"};
    const char *path = fuzz_file(names[data[0] % 5], data + 1, size - 1);
    stamp_source src;
    og_error err;
    if (stamp_find(path, NULL, NULL, &src, &err) == 0) stamp_source_free(&src);
    return 0;
}
