// A text field that shows a value until it is typed into, for values a command sets
// (the mask editor's and the rule editor's ranges): while it has the keyboard it keeps
// what is typed; Enter hands the text over; otherwise it shows `shown` again, so an
// undo or a command from the console shows at once.
#ifndef OROGEN_APP_VALUE_FIELD_H
#define OROGEN_APP_VALUE_FIELD_H

#include "ui/ui.h"

// 1 on Enter (buf holds the typed text), 0 otherwise.
int value_field(ui_context *ui, const char *label, char *buf, size_t len, const char *shown,
                const char *tip);

#endif
