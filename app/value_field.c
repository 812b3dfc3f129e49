#include "app/value_field.h"

#include <stdio.h>

int value_field(ui_context *ui, const char *label, char *buf, size_t len, const char *shown,
                const char *tip) {
    int rc = ui_textbox_flags(ui, label, buf, len, UI_TEXTBOX_SELECT_ALL);
    if (tip) ui_tooltip(ui, tip);
    if (rc & UI_TEXT_SUBMIT) return 1;
    if (!ui_last_focused(ui)) snprintf(buf, len, "%s", shown);
    return 0;
}
