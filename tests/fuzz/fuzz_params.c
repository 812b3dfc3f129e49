// libFuzzer target: the parameter-file reader (syntax, the refusal of what is not a
// parameter file, every key's value parsing and the whole-file checks).
#include "editor/params/world_params.h"
#include "fuzz_support.h"
#include "io/param_file.h"

#include <stdlib.h>

static void quiet(void *user, const char *message) {
    (void)user, (void)message;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    param_file pf;
    if (param_file_parse((const char *)data, size, &pf) == 0) param_file_free(&pf);
    // Both kinds: the extension picks the defaults.
    const char *names[2] = {"f.world", "f.planet"};
    const char *path = fuzz_file(names[size & 1], data, size);
    world_params p;
    int errors = 0;
    og_error err;
    if (world_params_load(path, &p, &errors, quiet, NULL, &err) == 0) {
        char *text = world_params_format(&p);
        if (!text) abort();
        free(text);
    }
    world_params_check_file(path, &err);
    return 0;
}
