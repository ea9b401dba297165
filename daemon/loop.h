/* A tiny event loop in the style of Redis's ae.c: file descriptors watched with poll(2) for reading or
 * writing, plus periodic timers. One thread runs it; other threads wake it with loop_wake(). */
#ifndef AALABD_LOOP_H
#define AALABD_LOOP_H

#include <stdbool.h>

#define LOOP_READ 1
#define LOOP_WRITE 2

struct loop;
typedef void (*loop_fd_fn)(struct loop *loop, int fd, int events, void *data);
typedef void (*loop_timer_fn)(struct loop *loop, void *data);

struct loop *loop_create(void);
void loop_destroy(struct loop *loop);
/* Watches fd for the events in mask (LOOP_READ | LOOP_WRITE); a second call for the same fd changes the
 * mask, the callback and data. mask 0 keeps the fd registered but unwatched. */
int loop_watch(struct loop *loop, int fd, int mask, loop_fd_fn fn, void *data);
void loop_unwatch(struct loop *loop, int fd);
/* Calls fn every interval_ms milliseconds (at most 16 timers). */
int loop_every(struct loop *loop, int interval_ms, loop_timer_fn fn, void *data);
/* Runs until loop_stop(); returns 0, or -1 if poll(2) failed. */
int loop_run(struct loop *loop);
void loop_stop(struct loop *loop);
/* Async-signal-safe and thread-safe: makes poll return so the wake callback runs in the loop thread. */
void loop_wake(struct loop *loop);
void loop_on_wake(struct loop *loop, loop_timer_fn fn, void *data);
/* Milliseconds on the monotonic clock. */
double loop_now_ms(void);

#endif
