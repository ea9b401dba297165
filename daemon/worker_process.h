/* The worker process (allow-user-methods), owned by the worker thread: worker_process.c. */
#ifndef AALABD_WORKER_PROCESS_H
#define AALABD_WORKER_PROCESS_H

#include <stddef.h>

struct store;
struct job;

/* Starts it and waits until it has opened the device (aalabd's start-up); -1 with a message in err. */
int worker_process_start(struct store *s, char *err, size_t err_size);
/* Runs one job in it (the worker thread), stopping it at the job's time limit or when it dies. */
void worker_process_run_job(struct store *s, struct job *job);
/* Ends it (the worker thread, at shutdown). */
void worker_process_stop(struct store *s);
/* The process's main: `aalabd --worker-process FD [--state-dir DIR] [--device SEL] [--scene-cache-bytes N]`. */
int worker_process_main(int argc, char **argv);

#endif
