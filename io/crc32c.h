// CRC32C (Castagnoli), the checksum of tile blobs and of recovery journal records.
// Check value: crc32c_update(0, "123456789", 9) = 0xE3069283.
#ifndef OROGEN_IO_CRC32C_H
#define OROGEN_IO_CRC32C_H

#include <stddef.h>
#include <stdint.h>

// The CRC of data continuing from crc (0 to start). Thread-safe.
uint32_t crc32c_update(uint32_t crc, const void *data, size_t n);

#endif
