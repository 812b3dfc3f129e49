// What kind of thing a path names, for the checks every read and write makes: a write
// never replaces a device node, FIFO or socket (rename would put a file where /dev/null
// was), and a read never opens one (a FIFO or /dev/full blocks or never ends).
#ifndef OROGEN_IO_FILE_KIND_H
#define OROGEN_IO_FILE_KIND_H

#include "io/err.h"

// -1 with err ("PATH is a FIFO (named pipe), not a file: not replaced") when path names
// a device, FIFO or socket; 0 otherwise (nothing there, a file, a symlink to a file).
int file_kind_check_replace(const char *path, og_error *err);
// -1 with err when path names a device, FIFO, socket or folder: reading it would block,
// never end or mean nothing; 0 otherwise (missing files are the reader's to report).
int file_kind_check_read(const char *path, og_error *err);
// "a FIFO (named pipe)", "a character device", ... for a stat mode; NULL for a file.
const char *file_kind_special(unsigned mode);

#endif
