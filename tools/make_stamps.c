// Writes the built-in stamp library: make_stamps FOLDER (resources/stamps in the repo).
#include "editor/tools/stamp_library.h"

#include <stdio.h>

int main(int argc, char **argv) {
    if (argc != 2) {
        fprintf(stderr, "usage: make_stamps FOLDER\n");
        return 2;
    }
    og_error err;
    if (stamp_library_generate(argv[1], &err) != 0) {
        fprintf(stderr, "make_stamps: %s\n", err.msg);
        return 1;
    }
    for (int i = 0; i < stamp_library_count(); i++)
        printf("%s/%s.png\n", argv[1], stamp_library_entry_at(i)->name);
    return 0;
}
