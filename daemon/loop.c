/* The event loop: a table of watched descriptors rebuilt into a pollfd array on each turn, timers
 * checked after every poll, and a self-pipe that signal handlers and the GPU worker write to. */
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "loop.h"

#define LOOP_MAX_TIMERS 16

struct watch {
	int fd;          /* -1: free slot */
	int mask;
	loop_fd_fn fn;
	void *data;
};

struct timer {
	int interval_ms;
	double due;
	loop_timer_fn fn;
	void *data;
};

struct loop {
	struct watch *watches;
	int watch_count, watch_cap;
	struct pollfd *pfds;
	struct timer timers[LOOP_MAX_TIMERS];
	int timer_count;
	int wake_pipe[2];
	loop_timer_fn wake_fn;
	void *wake_data;
	volatile int stopping;
};

double loop_now_ms(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return ts.tv_sec * 1000.0 + ts.tv_nsec / 1e6;
}

struct loop *loop_create(void)
{
	struct loop *loop = calloc(1, sizeof *loop);
	if (!loop)
		return NULL;
	if (pipe2(loop->wake_pipe, O_NONBLOCK | O_CLOEXEC) < 0) {
		free(loop);
		return NULL;
	}
	return loop;
}

void loop_destroy(struct loop *loop)
{
	if (!loop)
		return;
	close(loop->wake_pipe[0]);
	close(loop->wake_pipe[1]);
	free(loop->watches);
	free(loop->pfds);
	free(loop);
}

static struct watch *find(struct loop *loop, int fd)
{
	for (int i = 0; i < loop->watch_count; i++)
		if (loop->watches[i].fd == fd)
			return &loop->watches[i];
	return NULL;
}

int loop_watch(struct loop *loop, int fd, int mask, loop_fd_fn fn, void *data)
{
	struct watch *w = find(loop, fd);
	if (!w)
		w = find(loop, -1);
	if (!w) {
		if (loop->watch_count == loop->watch_cap) {
			int cap = loop->watch_cap ? loop->watch_cap * 2 : 16;
			struct watch *nw = realloc(loop->watches, (size_t)cap * sizeof *nw);
			struct pollfd *np = realloc(loop->pfds, ((size_t)cap + 1) * sizeof *np);
			if (nw)
				loop->watches = nw;
			if (np)
				loop->pfds = np;
			if (!nw || !np)
				return -1;
			loop->watch_cap = cap;
		}
		w = &loop->watches[loop->watch_count++];
	}
	*w = (struct watch){.fd = fd, .mask = mask, .fn = fn, .data = data};
	return 0;
}

void loop_unwatch(struct loop *loop, int fd)
{
	struct watch *w = find(loop, fd);
	if (w)
		w->fd = -1; /* the slot is reused; a callback already collected for fd this turn is skipped */
}

int loop_every(struct loop *loop, int interval_ms, loop_timer_fn fn, void *data)
{
	if (loop->timer_count == LOOP_MAX_TIMERS)
		return -1;
	loop->timers[loop->timer_count++] = (struct timer){interval_ms, loop_now_ms() + interval_ms, fn, data};
	return 0;
}

void loop_stop(struct loop *loop)
{
	loop->stopping = 1;
	loop_wake(loop);
}

void loop_wake(struct loop *loop)
{
	int saved = errno;
	/* a full pipe already means "wake up": EAGAIN is fine */
	ssize_t n = write(loop->wake_pipe[1], "x", 1);
	(void)n;
	errno = saved;
}

void loop_on_wake(struct loop *loop, loop_timer_fn fn, void *data)
{
	loop->wake_fn = fn;
	loop->wake_data = data;
}

static int next_timeout(struct loop *loop)
{
	if (loop->timer_count == 0)
		return -1;
	double now = loop_now_ms(), first = loop->timers[0].due;
	for (int i = 1; i < loop->timer_count; i++)
		if (loop->timers[i].due < first)
			first = loop->timers[i].due;
	return first <= now ? 0 : (int)(first - now) + 1;
}

static void run_timers(struct loop *loop)
{
	double now = loop_now_ms();
	for (int i = 0; i < loop->timer_count; i++) {
		struct timer *t = &loop->timers[i];
		if (t->due <= now) {
			t->due = now + t->interval_ms;
			t->fn(loop, t->data);
		}
	}
}

int loop_run(struct loop *loop)
{
	while (!loop->stopping) {
		int n = 0;
		loop->pfds[0] = (struct pollfd){.fd = loop->wake_pipe[0], .events = POLLIN};
		/* pfds has watch_cap + 1 slots; slot 0 is the wake pipe */
		for (int i = 0; i < loop->watch_count; i++) {
			struct watch *w = &loop->watches[i];
			short ev = (short)(((w->mask & LOOP_READ) ? POLLIN : 0) | ((w->mask & LOOP_WRITE) ? POLLOUT : 0));
			loop->pfds[1 + n++] = (struct pollfd){.fd = w->fd >= 0 && ev ? w->fd : -1, .events = ev};
		}
		int rc = poll(loop->pfds, (nfds_t)n + 1, next_timeout(loop));
		if (rc < 0 && errno != EINTR)
			return -1;
		if (rc > 0 && (loop->pfds[0].revents & POLLIN)) {
			char drain[64];
			while (read(loop->wake_pipe[0], drain, sizeof drain) > 0)
				;
			if (loop->wake_fn)
				loop->wake_fn(loop, loop->wake_data);
		}
		for (int i = 0; rc > 0 && i < n && !loop->stopping; i++) {
			struct pollfd *p = &loop->pfds[1 + i];
			if (p->fd < 0 || !p->revents)
				continue;
			struct watch *w = &loop->watches[i];
			if (w->fd != p->fd) /* unwatched (or replaced) by an earlier callback this turn */
				continue;
			int events = 0;
			if (p->revents & (POLLIN | POLLHUP | POLLERR))
				events |= LOOP_READ;
			if (p->revents & (POLLOUT | POLLERR))
				events |= LOOP_WRITE;
			w->fn(loop, w->fd, events & (w->mask | LOOP_READ), w->data);
		}
		run_timers(loop);
	}
	return 0;
}
