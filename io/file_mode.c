#include "io/file_mode.h"

#include <stdio.h>
#include <sys/stat.h>

mode_t og_new_file_mode(void) {
    // /proc/self/status reads the umask without changing it (umask() can only read it
    // by setting it, which would race with other threads creating files).
    unsigned mask = 022;
    FILE *f = fopen("/proc/self/status", "r");
    if (f) {
        char line[256];
        while (fgets(line, sizeof line, f))
            if (sscanf(line, "Umask: %o", &mask) == 1) break;
        fclose(f);
    }
    return (mode_t)(0666 & ~mask);
}
