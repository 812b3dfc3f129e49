// Dragging a row of a list to another place (the Layers panel's layers, the Materials
// panel's rules): a left press on a row's widget, a move of more than half a line, and
// the release over another row moves it there. The caller runs the command that does.
#ifndef OROGEN_APP_ROW_DRAG_H
#define OROGEN_APP_ROW_DRAG_H

#include "ui/ui.h"

typedef struct row_drag {
    int pressed; // 1 + the row the left button went down on (0: none)
    float press_y;
    int dragging; // it moved far enough to be a drag
} row_drag;

// After a row's widget (the last one built): a left press on it may start a drag.
void row_drag_watch(row_drag *d, const ui_context *ui, int row);
// Whether the pressed row is being dragged (its click is not a click).
int row_drag_active(const row_drag *d);
// After every row (rows[i]: row i's rectangle, rows of count in any order on screen):
// while a drag goes on, a line where the row would land; on the release over another
// row, 1 with *from and *to (0 otherwise).
int row_drag_update(row_drag *d, ui_context *ui, const ui_rect *rows, int count, int *from,
                    int *to);

#endif
