// The user's stamp folder: an image file becomes a user stamp by being copied into it
// (the editor's drag-and-drop, the `stamp_add` command).
#ifndef OROGEN_EDITOR_STAMP_USER_H
#define OROGEN_EDITOR_STAMP_USER_H

#include "io/err.h"

#include <stddef.h>

// Copies the image at path into user_dir (created if missing) as NAME.EXT, written
// atomically. NAME is name, or the file's own name without its extension when name is
// NULL or empty; it must be letters, digits, '_' and '-' and must not be a built-in
// stamp's. When NAME is taken, NAME_2, NAME_3, ... is used. The image must read as
// one (the error names the file). The stamp's name goes to out_name.
int stamp_user_add(const char *path, const char *name, const char *resource_dir,
                   const char *user_dir, char *out_name, size_t out_size, og_error *err);

#endif
