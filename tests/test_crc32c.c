// CRC32C (io/crc32c.c) against the bitwise definition (reflected polynomial 0x82F63B78)
// over random buffers of every length class the fast paths split: under a word, under
// three lanes, many three-lane blocks with tails, continued from any split point,
// from any alignment; and the standard check value.
#include "io/crc32c.h"

#include <stdlib.h>
#include <string.h>

#include <stdarg.h>
#include <setjmp.h>
#include <stddef.h>
#include <cmocka.h>

static uint64_t rng = 0x2545f4914f6cdd1dull;
static uint32_t next_u32(void) {
    rng ^= rng << 13, rng ^= rng >> 7, rng ^= rng << 17;
    return (uint32_t)(rng >> 32);
}

static uint32_t bitwise(uint32_t crc, const uint8_t *p, size_t n) {
    crc = ~crc;
    while (n--) {
        crc ^= *p++;
        for (int k = 0; k < 8; k++)
            crc = (crc >> 1) ^ (0x82F63B78u & (0u - (crc & 1)));
    }
    return ~crc;
}

static void test_check_value(void **state) {
    (void)state;
    assert_int_equal(crc32c_update(0, "123456789", 9), 0xE3069283u);
}

static void test_matches_bitwise(void **state) {
    (void)state;
    enum { MAX = 3 * 3 * 4096 + 77 };
    uint8_t *buf = malloc(MAX + 8);
    assert_non_null(buf);
    for (size_t i = 0; i < MAX + 8; i++)
        buf[i] = (uint8_t)next_u32();
    const size_t lengths[] = {0,     1,     7,     8,     9,     100,   4095, 4096,
                              12287, 12288, 12289, 24576, 24583, 30000, MAX};
    for (size_t l = 0; l < sizeof lengths / sizeof *lengths; l++)
        for (size_t align = 0; align < 8; align += 3) {
            size_t n = lengths[l];
            const uint8_t *p = buf + align;
            uint32_t want = bitwise(0x12345678u, p, n);
            assert_int_equal(crc32c_update(0x12345678u, p, n), want);
            size_t split = n ? next_u32() % n : 0; // continued from a split point
            assert_int_equal(
                crc32c_update(crc32c_update(0x12345678u, p, split), p + split, n - split), want);
        }
    free(buf);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_check_value),
        cmocka_unit_test(test_matches_bitwise),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
