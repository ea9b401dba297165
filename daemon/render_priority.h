#ifndef AALABD_RENDER_PRIORITY_H
#define AALABD_RENDER_PRIORITY_H

#include "run/engine.h"

/* render_priority.c: the rendering threads' nice value, render_nice above the calling thread's (at most 19);
 * setting it on the calling thread; the engine created on a thread at that value, so that the device's
 * threads start there (aalabd(8), render-nice). */
int render_nice_value(int render_nice);
void render_priority_apply(int nice_value);
int render_engine_create(const struct aa_engine_options *options, int nice_value, struct aa_engine **engine,
			 struct aa_error *err);

#endif
