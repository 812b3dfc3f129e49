#include "app/world_warnings.h"

#include <pthread.h>
#include <stdio.h>

// One inbox per process, as there is one window.
static struct {
    pthread_mutex_t lock;
    char text[WORLD_WARNINGS_KEPT][1024];
    int first, count;
} inbox = {.lock = PTHREAD_MUTEX_INITIALIZER};

static void report(void *user, const char *message) {
    (void)user;
    fprintf(stderr, "%s\n", message);
    pthread_mutex_lock(&inbox.lock);
    if (inbox.count == WORLD_WARNINGS_KEPT) { // the oldest goes
        inbox.first = (inbox.first + 1) % WORLD_WARNINGS_KEPT;
        inbox.count--;
    }
    int at = (inbox.first + inbox.count) % WORLD_WARNINGS_KEPT;
    snprintf(inbox.text[at], sizeof inbox.text[at], "%s", message);
    inbox.count++;
    pthread_mutex_unlock(&inbox.lock);
}

void world_warnings_install(world_settings *settings) {
    settings->warn = report;
    settings->warn_user = NULL;
}

int world_warnings_take(char *out, size_t size) {
    pthread_mutex_lock(&inbox.lock);
    int any = inbox.count > 0;
    if (any) {
        snprintf(out, size, "%s", inbox.text[inbox.first]);
        inbox.first = (inbox.first + 1) % WORLD_WARNINGS_KEPT;
        inbox.count--;
    }
    pthread_mutex_unlock(&inbox.lock);
    return any;
}
