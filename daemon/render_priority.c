/* Rendering below the protocol loop's priority (render-nice, aalabd(8)). lavapipe renders on every core; at
 * the loop's own priority a ping that arrived during a render waited for a time slice behind it
 * (bench/service, load average 4-5: ping p99 during a render 7.6 ms at the same priority, 0.1 ms with the
 * rendering threads 5 nice levels lower). Linux keeps a nice value per thread, and a new thread or process
 * starts with its creator's: threads that set theirs before creating the device, its compiler or the
 * worker process pass it on to all the rendering threads, and the loop thread keeps its own. */
#include <errno.h>
#include <pthread.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include "render_priority.h"

int render_nice_value(int render_nice)
{
	errno = 0;
	int base = getpriority(PRIO_PROCESS, (id_t)syscall(SYS_gettid));
	if (base == -1 && errno)
		base = 0;
	int v = base + render_nice;
	return v > 19 ? 19 : v;
}

void render_priority_apply(int nice_value)
{
	/* raising a nice value needs no privilege; a failure leaves the thread at the loop's priority */
	(void)setpriority(PRIO_PROCESS, (id_t)syscall(SYS_gettid), nice_value);
}

struct engine_start {
	const struct aa_engine_options *options;
	struct aa_engine **engine;
	struct aa_error *err;
	int nice_value, rc;
};

static void *engine_start_main(void *arg)
{
	struct engine_start *e = arg;
	render_priority_apply(e->nice_value);
	e->rc = aa_engine_create(e->options, e->engine, e->err);
	return NULL;
}

int render_engine_create(const struct aa_engine_options *options, int nice_value, struct aa_engine **engine,
			 struct aa_error *err)
{
	struct engine_start e = {options, engine, err, nice_value, -1};
	pthread_t t;
	if (pthread_create(&t, NULL, engine_start_main, &e) != 0)
		return aa_engine_create(options, engine, err); /* at the loop's priority rather than not at all */
	pthread_join(t, NULL);
	return e.rc;
}
