// The parameters that fully describe a world's unedited terrain, and their
// parameter-file form (`name.world` / `name.planet`). Planet files written with
// Kahoun 2010's keys (generator, radius, max_height, ocean_level, omega, seed,
// w_factor, exponent) load unchanged.
#ifndef OROGEN_EDITOR_WORLD_PARAMS_H
#define OROGEN_EDITOR_WORLD_PARAMS_H

#include "editor/layers/layer_table.h"
#include "editor/layers/material_rules.h"
#include "io/err.h"

#include <stddef.h>
#include <stdint.h>

typedef enum world_kind { WORLD_FLAT = 0, WORLD_PLANET = 1 } world_kind;

// Generator indices are what `generator N` and `generator = N;` accept. 0 and 1 are
// Kahoun 2010's two generators (simple and advanced fBm), so its files keep their meaning.
typedef enum gen_kind {
    GEN_FBM = 0,            // fBm over Perlin gradient noise (fractional octaves)
    GEN_FBM_ADVANCED = 1,   // fBm + Kahoun 2010's ocean-floor root and exponent shaping
    GEN_RIDGED = 2,         // Musgrave's ridged multifractal
    GEN_DIAMOND_SQUARE = 3, // Harris 2011's diamond-square, seamless over int32 tiles
    GEN_FAULTS = 4,         // random fault lines
    GEN_FLAT = 5,           // constant height (base_height)
    GEN_PLANET = 6,         // warped continents, ridged ranges in belts, ridged hills
    GEN_CRATERS = 7,        // GEN_FBM_ADVANCED with impact craters at every scale
    GEN_COUNT
} gen_kind;

// Longest coordinate reference system text a world keeps (a parameter file line is 4096).
#define WORLD_CRS_MAX 3584
// Room for any key's value as text (world_params_get).
#define WORLD_VALUE_MAX 4096

// A world's id: 128 random bits as lowercase hex.
#define WORLD_ID_CHARS 32

typedef struct world_params {
    world_kind kind;
    gen_kind generator;
    int64_t seed;         // any integer; the generators use it modulo 2^32
    double octaves;       // fBm octave count, fractional allowed (Kahoun 2010)
    double w_factor;      // fBm gain: weight multiplier per octave
    double exponent;      // fBm lacunarity: frequency multiplier per octave
    double max_height;    // metres: generated heights lie in (-max_height, max_height)
    double ocean_level;   // flat: metres above the datum; planets: the sea's radius (seed 004)
    double radius;        // planets: metres from the centre to the datum
    double omega;         // planets: angular velocity, radians per second (Kahoun 2010)
    double atmosphere;    // planets: air relative to Earth's (1), 0 = none
    double spacing;       // metres between coarse samples
    int64_t size;         // flat worlds: coarse samples along X (and Z); 0 = unbounded
    int64_t size_z;       // flat worlds: coarse samples along Z when not square; 0 = size
    int32_t detail_ratio; // detail samples per coarse sample, per side
    int32_t volume_ratio; // volume voxels per coarse spacing (voxel = spacing / volume_ratio)
    double feature_size;  // metres: wavelength of the lowest octave; 0 = automatic
    double base_height;   // metres added to every generated height (flat generator's height)
    double roughness;     // diamond-square: first displacement, as a fraction of max_height
    double smoothing;     // diamond-square: roughness multiplier per subdivision
    double ridge_offset;  // ridged multifractal: offset subtracted from |noise|
    int32_t fault_count;  // faults: number of fault lines per 64 km x 64 km cell
    // Georeferenced worlds (made from a DEM): the source's coordinate reference system
    // (WKT, or an authority code such as EPSG:4326; "" = none) and GDAL's geotransform
    // from coarse sample (column, row) to its coordinates (all 0 = none).
    char geo_crs[WORLD_CRS_MAX];
    double geo_transform[6];
    char tiles[1024]; // tile store path as written (relative to the file); "" = name.tiles
    // What the file was saved with, so a missing, emptied or swapped store is noticed:
    // the world's id (also in its tile store's meta table; "" = not recorded) and the
    // count of tiles the store held (-1 = not recorded). Written by save.
    char tiles_id[WORLD_ID_CHARS + 1];
    int64_t tiles_saved;
    // The edit layers over the generated terrain (`layer.I = ...;` lines); empty in a file
    // from before layers (the world then gives it one, editor/world/world.h).
    layer_table layers;
    // The automatic material rules (`material_rule_N = ...;` lines); the default stack
    // for a file without them.
    material_rules material_rules;
} world_params;

// The built-in defaults for a kind (a pleasant landscape or an Earth-like planet).
void world_params_default(world_params *p, world_kind kind);
// Coarse samples along Z of a bounded flat world (size_z, else size; 0 = unbounded).
static inline int64_t world_params_size_z(const world_params *p) {
    return p->size_z > 0 ? p->size_z : p->size;
}

// The sea's height above the datum in metres, whatever the kind (planets keep
// ocean_level as a radius, as seed 004's files do).
double world_params_ocean_height(const world_params *p);

// Generator names: "fbm", "fbm_advanced", "ridged", "diamond_square", "faults", "flat".
const char *gen_kind_name(gen_kind g);
// Accepts a name or an index; returns -1 if neither.
int gen_kind_parse(const char *text);

// Sets one key from its text value. Returns 0, or -1 with err describing the bad value
// ("seed: expected an integer, got 'abc'"); the parameter is unchanged on error.
// Unknown keys return 1 (callers warn).
int world_params_set(world_params *p, const char *key, const char *value, og_error *err);
// world_params_set, and the keys a file has besides them: the edit layers' lines
// (layer_table_read_entry) and the material rules' (material_rules_read_entry). What the
// file readers call; `set` knows only the keys.
int world_params_read_entry(world_params *p, const char *key, const char *value, og_error *err);

// Formats one key's value (canonical text) into buf; returns -1 for unknown keys.
int world_params_get(const world_params *p, const char *key, char *buf, size_t len);

// Every key, in canonical order, for `params`, `set` and the writer.
size_t world_params_key_count(void);
const char *world_params_key(size_t i);
const char *world_params_key_help(const char *key); // one-line description, NULL if unknown

// Checks cross-field constraints (spacing > 0, size within limits, ...). Returns 0 or
// -1 with err naming the field.
int world_params_validate(const world_params *p, og_error *err);

// Loads a parameter file. The kind defaults from the extension (.planet -> planet)
// unless the file sets `kind`. Bad values are reported as "path:line: error: ..." and
// keep their default; unknown keys as "path:line: warning: ...". All messages go
// to report (one call per message, no trailing newline) when it is not NULL.
// Returns 0 when the file was read (even with diagnostics; *errors counts the errors),
// -1 when it could not be read at all or is not a parameter file (err names the path:
// "PATH: not an Orogen world or planet parameter file (why)" for bytes that are not
// UTF-8 text or text in which no line sets a known key; nothing is reported then).
int world_params_load(const char *path, world_params *p, int *errors,
                      void (*report)(void *user, const char *message), void *user, og_error *err);

// world_params_load that also checks the seal save writes: a file Orogen saved that
// lacks it was cut short; cut_short (unless NULL) then says so, naming the keys it lacks
// ("" for a whole file), and an error is reported.
int world_params_load_whole(const char *path, world_params *p, int *errors,
                            void (*report)(void *user, const char *message), void *user,
                            char *cut_short, size_t cut_len, og_error *err);

// 0 when path reads as a parameter file world_params_load would take; -1 with err
// naming the path and why otherwise (unreadable, not text, no known key).
int world_params_check_file(const char *path, og_error *err);

// Writes the canonical file: a header, then for each key a `# comment` line and
// `key = value;`, then the seal (world_params_seal_check). Floats are printed so that they read
// back bit-exactly. Atomic (see param_file_write_atomic).
int world_params_save(const char *path, const world_params *p, og_error *err);
// Whether a parameter file's text is whole: 0 when it is (or was written by hand, or by
// an Orogen before files were sealed: no "Saved by Orogen" line); 1 when Orogen saved it
// and its seal (the last line save writes) is missing (cut short), or the text changed
// and lost keys (damaged); why names the keys it lacks; 2 when the seal is there, the
// text before it changed but every key is still set (edited by hand: read as it is,
// unless a line then does not read, which the loader takes for damage).
int world_params_seal_check(const char *text, size_t len, char *why, size_t why_len);
// The canonical text alone (malloc'd, NUL-terminated).
char *world_params_format(const world_params *p);

// Resolves the tile store path for a parameter file at param_path into out: relative
// to the parameter file's folder; must stay inside that folder (no absolute paths, no
// `..` escaping it). Returns -1 with err naming the `tiles` value otherwise.
int world_params_tiles_path(const world_params *p, const char *param_path, char *out, size_t len,
                            og_error *err);

#endif
