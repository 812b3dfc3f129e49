// Sending a clip window's changed texels to its GPU texture: the one upload loop the
// flat viewport's windows and the planet's detail windows share.
#ifndef OROGEN_RENDERER_CLIP_WINDOW_UPLOAD_H
#define OROGEN_RENDERER_CLIP_WINDOW_UPLOAD_H

#include "renderer/clip_window.h"

#include <epoxy/gl.h>
#include <stdint.h>

// Uploads the rectangles the window changed (all of it after a refill) to tex (layer >= 0:
// that layer of a 2D array texture) and clears the window's list. Returns the texels sent.
uint64_t clip_window_upload(clip_window *w, GLuint tex, int layer, GLenum format, GLenum type);

#endif
