// The console's ui_messages: what the editor's UI shows the user now (a notice over the
// viewport, an error in a dialog, a slider's refusal of typed text), from the UI's last
// frame, so tests check that a failure is shown where the user acted.
#ifndef OROGEN_APP_UI_MESSAGES_H
#define OROGEN_APP_UI_MESSAGES_H

#include "io/err.h"
#include "ui/ui.h"

// The window's UI contexts (the editor's and the one shown over long work; NULL: none).
void ui_messages_attach(const ui_context *editor, const ui_context *busy);
int ui_messages_register(og_error *err);

#endif
