#include "io/module_load.h"

#include <dlfcn.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

void *module_open(const char *env_var, const char *file_name, const char *build_path, char *why,
                  size_t why_len) {
    char installed[PATH_MAX + 64] = "";
    char exe[PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n > 0) {
        exe[n] = 0;
        char *slash = strrchr(exe, '/');
        if (slash) *slash = 0;
        snprintf(installed, sizeof installed, "%s/../lib/orogen/%s", exe, file_name);
    }
    const char *candidates[] = {getenv(env_var), installed, build_path};
    snprintf(why, why_len, "%s not found", file_name);
    for (size_t i = 0; i < sizeof candidates / sizeof candidates[0]; i++) {
        if (!candidates[i] || !*candidates[i] || access(candidates[i], R_OK) != 0) continue;
        void *h = dlopen(candidates[i], RTLD_NOW | RTLD_LOCAL);
        if (h) return h;
        snprintf(why, why_len, "%s", dlerror());
    }
    return NULL;
}
