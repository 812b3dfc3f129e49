// The Layers panel's own state (app/layers_panel.c): the edit layers' rows (rename,
// drag to reorder) and the mask editor. Only what must last between frames; the stack
// itself is read from the world each frame and changed only by layer commands.
#ifndef OROGEN_APP_LAYERS_PANEL_STATE_H
#define OROGEN_APP_LAYERS_PANEL_STATE_H

#include "app/row_drag.h"
#include "editor/layers/layer_table.h"
#include "editor/world/terrain_histogram.h"

typedef struct layers_panel_state {
    int32_t renaming;            // id of the layer whose name is being typed (0: none)
    int rename_seen;             // its field has had the keyboard
    char rename[LAYER_NAME_MAX]; // the name typed so far
    row_drag drag;               // a layer's name dragged to another place in the stack
    int32_t mask_layer;          // id of the layer whose mask is being edited (0: none)
    layer_mask draft;            // its mask as dragged so far (the overlay shows it)
    int draft_live;              // a range is being dragged: the draft is not the layer's
    terrain_histogram hist;      // the composite around the view, its terms binned
    terrain_flow_field flow;     // the flow there, for the overlay (freed by editor_ui_destroy)
    unsigned flow_serial;        // counts the fields read
    int hist_valid;              // hist was read, for hist_step of the history
    size_t hist_step;            // the history position it was read at
    double hist_at[2];           // and the camera's place then
    char hist_error[256];        // why it could not be read ("" when it was)
    char fields[4][3][32];       // the terms' low, high and edge fields as typed
    char field_error[160];       // a typed number that is none, said under the fields
} layers_panel_state;

#endif
