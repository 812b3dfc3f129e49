// Each tool's settings kept between runs (Terrain3D #547): when the editor closes the
// settings of every tool used are written into the editor's settings; when it opens
// they come back as `tool NAME key=value ...` commands (so a recording of the session
// holds them and replays exactly).
#ifndef OROGEN_APP_TOOL_SETTINGS_H
#define OROGEN_APP_TOOL_SETTINGS_H

#include "app/settings.h"
#include "editor/cmd/context.h"

// The settings of every tool ctx remembers, and the tool in use, into s.
void tool_settings_capture(const cmd_context *ctx, app_settings *s);
// Runs s's tool settings on ctx; a line the tool refuses is a warning naming path.
void tool_settings_restore(cmd_context *ctx, const app_settings *s, const char *path);

#endif
