// The benchmarks edit unsaved worlds, and every edit of an unsaved world is kept in a
// crash journal until it is saved or recovered: run from a user's shell they would leave
// megabytes of journals per run in the user's recovery folder (tens of GB after a day of
// benchmarking), each offered for recovery at the next start of the editor. A benchmark
// calls bench_journals_private() first: its journals (and those of the orogen processes
// it starts, which inherit the variable) go to a folder of its own, removed at exit.
#ifndef OROGEN_BENCH_JOURNALS_H
#define OROGEN_BENCH_JOURNALS_H

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

static char bench_journal_dir[64];

static inline void bench_journals_remove(void) {
    DIR *d = opendir(bench_journal_dir);
    if (!d) return;
    char path[400];
    for (struct dirent *e; (e = readdir(d));) {
        if (e->d_name[0] == '.') continue;
        snprintf(path, sizeof path, "%s/%s", bench_journal_dir, e->d_name);
        unlink(path);
    }
    closedir(d);
    rmdir(bench_journal_dir);
}

static inline void bench_journals_private(void) {
    snprintf(bench_journal_dir, sizeof bench_journal_dir, "/tmp/orogen-bench-recover-XXXXXX");
    if (!mkdtemp(bench_journal_dir)) {
        perror("bench: a folder for the crash journals");
        exit(1);
    }
    setenv("OROGEN_RECOVER_DIR", bench_journal_dir, 1);
    atexit(bench_journals_remove);
}

#endif
