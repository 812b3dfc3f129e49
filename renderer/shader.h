// GLSL programs built from files in the resources folder, with `#include "x.glsl"`
// and compile errors reported at the file and line a person has open in an editor.
#ifndef OROGEN_RENDERER_SHADER_H
#define OROGEN_RENDERER_SHADER_H

#include <epoxy/gl.h>

#include "io/err.h"

// Builds a program from vertex shader vs_name and fragment shader fs_name in dir
// (e.g. resources/shaders). A source line `#include "other.glsl"` is replaced by
// that file from the same dir (nested includes allowed; a cycle or nesting deeper
// than 8 is an error at the #include). Only the top-level file has the #version line.
// Returns the program, or 0 with err set:
//   "DIR/FILE:LINE: error: message"   compile error, at the line of the file that has it
//   "DIR/A, DIR/B: link error: message"
//   "PATH: cannot open: reason"
GLuint shader_program_load(const char *dir, const char *vs_name, const char *fs_name,
                           og_error *err);
// The same with a geometry shader between (gs_name NULL: none).
GLuint shader_program_load_gs(const char *dir, const char *vs_name, const char *gs_name,
                              const char *fs_name, og_error *err);
// The same with `defines` (e.g. "#define SEA\n#define BRUSH\n") after both stages'
// #version line: variants of one source without the branches a software renderer
// would run for every fragment (llvmpipe executes both sides of an `if`, masked).
// Errors keep the files' own line numbers.
GLuint shader_program_load_variant(const char *dir, const char *vs_name, const char *fs_name,
                                   const char *defines, og_error *err);
// The variant whose bits are set in `flags`: bit b defines names[b] (count names).
GLuint shader_program_load_flags(const char *dir, const char *vs_name, const char *fs_name,
                                 const char *const *names, int count, unsigned flags,
                                 og_error *err);

#endif
