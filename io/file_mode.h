// The mode a new file gets: 0666 less the process's umask, as open(O_CREAT) would give.
// Atomic writers create temp files with mkstemp (always 0600) and set this before the
// rename, so exports land with the same permissions as any file the user makes.
#ifndef OROGEN_IO_FILE_MODE_H
#define OROGEN_IO_FILE_MODE_H

#include <sys/types.h>

#ifdef __cplusplus
extern "C" {
#endif

mode_t og_new_file_mode(void);

#ifdef __cplusplus
}
#endif

#endif
