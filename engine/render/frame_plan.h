/* The frame plan: which passes a job runs, from what the scene contains and what the
 * chosen methods need, each with the reason it runs or is skipped. */
#ifndef AA_FRAME_PLAN_H
#define AA_FRAME_PLAN_H

#include <stdbool.h>

#include "types/job.h"
#include "scene/scene.h"

struct aa_frame_plan {
	bool shadow_map;     /* a light casts shadows */
	bool alpha_test;     /* some material is an alpha cut-out */
	bool velocity;       /* a method reprojects history */
	bool ids;            /* a method reads model IDs */
	bool history;        /* a method keeps history */
	bool supersampled;   /* a method renders at a higher resolution */
	unsigned needs;      /* union of the methods' AA_NEED_* bits */
	int entry_count;
	struct aa_plan_entry entries[AA_MAX_PASSES];
};

void aa_frame_plan_build(const struct aa_scene *scene, const struct aa_job_spec *spec,
			 struct aa_frame_plan *plan);

#endif
