// Shared by the libFuzzer targets: hands an input to code that reads files.
#ifndef OROGEN_FUZZ_SUPPORT_H
#define OROGEN_FUZZ_SUPPORT_H

#include <stddef.h>
#include <stdint.h>

// Writes data to a private file named NAME (so its extension is seen) in a folder of
// this process under $TMPDIR; returns its path (static storage, replaced next call).
const char *fuzz_file(const char *name, const uint8_t *data, size_t size);

#endif
