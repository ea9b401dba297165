/* Builds the frame plan: a pass is in it only when the scene's content or a chosen method calls for it. */
#include <stdio.h>
#include <string.h>

#include "frame_plan.h"

static void add(struct aa_frame_plan *plan, const char *pass, bool ran, const char *fmt, const char *arg)
{
	if (plan->entry_count >= AA_MAX_PASSES)
		return;
	struct aa_plan_entry *e = &plan->entries[plan->entry_count++];
	snprintf(e->pass, sizeof e->pass, "%s", pass);
	snprintf(e->reason, sizeof e->reason, fmt, arg ? arg : "");
	e->ran = ran;
}

static const char *first_method_needing(const struct aa_job_spec *spec, unsigned need)
{
	for (int i = 0; i < spec->method_count; i++) {
		const struct aa_method *m = spec->methods[i].method;
		unsigned needs = m->needs_fn ? m->needs_fn(&spec->methods[i].params) : m->needs;
		if (needs & need)
			return spec->methods[i].label;
	}
	return NULL;
}

void aa_frame_plan_build(const struct aa_scene *scene, const struct aa_job_spec *spec,
			 struct aa_frame_plan *plan)
{
	memset(plan, 0, sizeof *plan);
	for (int i = 0; i < spec->method_count; i++) {
		const struct aa_method *m = spec->methods[i].method;
		plan->needs |= m->needs_fn ? m->needs_fn(&spec->methods[i].params) : m->needs;
	}

	const char *shadow_light = NULL;
	for (int i = 0; i < scene->light_count && !shadow_light; i++)
		if (scene->lights[i].casts_shadow && scene->lights[i].type == AA_LIGHT_DIRECTIONAL)
			shadow_light = "a directional light casts shadows";
	plan->shadow_map = shadow_light != NULL;
	add(plan, "shadow-map", plan->shadow_map,
	    plan->shadow_map ? "%s" : "no light casts shadows", shadow_light);

	add(plan, "scene-forward", true, "%s",
	    "forward shading, Lambert + Blinn-Phong specular, reversed-Z float depth");

	plan->alpha_test = aa_scene_has_cutout(scene);
	add(plan, "alpha-test", plan->alpha_test,
	    plan->alpha_test ? "%s" : "no material is an alpha cut-out",
	    "cut-out materials are drawn with the discard pipeline");

	const char *who = first_method_needing(spec, AA_NEED_VELOCITY);
	plan->velocity = who != NULL;
	if (who)
		add(plan, "velocity", true, "%s reprojects history", who);
	else
		add(plan, "velocity", false, "%s", aa_scene_has_animation(scene)
		    ? "objects move, but no chosen method reprojects history"
		    : "nothing moves and no chosen method reprojects history");

	who = first_method_needing(spec, AA_NEED_IDS);
	plan->ids = who != NULL;
	add(plan, "model-ids", plan->ids, who ? "%s reads model IDs" : "no chosen method reads model IDs", who);

	who = first_method_needing(spec, AA_NEED_HISTORY);
	plan->history = who != NULL;
	add(plan, "history", plan->history, who ? "%s keeps history" : "no chosen method keeps history", who);

	who = first_method_needing(spec, AA_NEED_SUPERSAMPLED);
	plan->supersampled = who != NULL;
	add(plan, "supersample-resolve", plan->supersampled,
	    who ? "%s renders at a higher resolution and box-filters down" : "no chosen method supersamples",
	    who);

	char why[96];
	snprintf(why, sizeof why, "%d jittered renders accumulated in float (ground truth)",
		 spec->reference_samples);
	add(plan, "reference-accumulate", true, "%s", why);
	add(plan, "readback", true, "%s", "every output is read back for metrics and images");
}
