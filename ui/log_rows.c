#include "ui/log_rows.h"

static int continuation(unsigned char c) {
    return (c & 0xC0) == 0x80;
}

size_t log_row_bytes(const char *text, size_t cols) {
    size_t i = 0, chars = 0, space = 0; // space: bytes up to and including the last space
    while (text[i] && chars < cols) {
        if (text[i] == ' ' && chars >= cols / 2) space = i + 1;
        i++;
        while (continuation((unsigned char)text[i]))
            i++;
        chars++;
    }
    if (!text[i]) return i;           // the rest fits
    if (text[i] == ' ') return i + 1; // breaks at the row's end: the space goes with it
    return space ? space : i;
}

size_t log_rows(const char *text, size_t cols) {
    size_t rows = 0;
    do {
        text += log_row_bytes(text, cols);
        rows++;
    } while (*text);
    return rows;
}
