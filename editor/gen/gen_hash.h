// Integer hashing shared by the generators and the noise: well-mixed 32 bits from
// coordinates and seeds, the same on every machine.
#ifndef OROGEN_EDITOR_GEN_HASH_H
#define OROGEN_EDITOR_GEN_HASH_H

#include <stdint.h>

static inline uint32_t gen_hash32(uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}
static inline uint32_t gen_hash_3(uint32_t a, uint32_t b, uint32_t c) {
    return gen_hash32(a ^ gen_hash32(b ^ gen_hash32(c + 0x9e3779b9U)));
}
// Uniform in [-1, 1) from a hash.
static inline float gen_hash_unit(uint32_t h) {
    return (float)(int32_t)h * (1.0f / 2147483648.0f);
}

#endif
