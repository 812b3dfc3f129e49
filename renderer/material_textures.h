// Procedural material textures for terrain splatting: eight tileable albedo + height
// textures made on the CPU from periodic noise, deterministically and without assets.
#ifndef OROGEN_RENDERER_MATERIAL_TEXTURES_H
#define OROGEN_RENDERER_MATERIAL_TEXTURES_H

#define MATERIAL_TEXTURE_SIZE 256 // per side, power of two, tileable (wraps seamlessly)
#define MATERIAL_TEXTURE_COUNT 8

// The 8 textures, in array order: 0 sand, 1 grass, 2 rock, 3 snow, 4 dirt, 5 gravel,
// 6 moss, 7 cliff. NULL for an index out of range.
const char *material_texture_name(int index);

// Fills rgba (SIZE * SIZE * 4 bytes, rows top-first): RGB albedo in sRGB, A a relative
// height in 0..255 for height-based blending between materials. The same bytes on
// every machine, and the texture wraps with no seam. Meant to be seen at about 1-4 m
// per repeat. An index out of range fills mid grey.
void material_texture_generate(int index, unsigned char *rgba);

#endif
