/* Builds the frame plan: a pass is in it only when the scene's content or a chosen method calls for it. */
#include <stdio.h>
#include <string.h>
#include <strings.h>

#include "render/frame_plan.h"
#include "render/shadow_fit.h"

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

/* Whether the job's camera path moves the camera at all (the reason velocity gives when no method needs it). */
static bool path_moves(const struct aa_scene *scene, const char *name)
{
	const struct aa_camera_path *p = aa_scene_find_path(scene, name);
	if (!p || strcmp(name, "static") == 0)
		return false;
	switch (p->kind) {
	case AA_PATH_STATIC: return false;
	case AA_PATH_ORBIT: case AA_PATH_PAN: return p->degrees != 0.0f;
	case AA_PATH_DOLLY: return p->distance != 0.0f;
	case AA_PATH_KEYFRAMES: break;
	}
	for (int k = 1; k < p->key_count; k++)
		if (memcmp(&p->keys[k].camera, &p->keys[0].camera, sizeof p->keys[0].camera) != 0)
			return true;
	return false;
}

/* For cut-outs (blend false) or blending: the first object (file order) drawing with such a material, said
 * as the plan's reason, and the names of all such materials (used or not). */
static void material_use(const struct aa_scene *scene, bool blend, char *used, size_t used_size, char *unused,
			 size_t unused_size)
{
	used[0] = unused[0] = '\0';
	for (int o = 0; o < scene->object_count && !used[0]; o++) {
		const struct aa_material *m = &scene->materials[scene->objects[o].material_index];
		if (blend ? m->blend : (m->alpha_cutout && !m->blend))
			snprintf(used, used_size, "material '%.40s' (object '%.30s') is %s", m->name, scene->objects[o].name,
				 blend ? "blended: drawn after opaque objects, farthest first" : "an alpha cut-out");
	}
	for (int i = 0; i < scene->material_count; i++) {
		const struct aa_material *m = &scene->materials[i];
		size_t len = strlen(unused);
		if ((blend ? m->blend : m->alpha_cutout) && len + 8 < unused_size)
			snprintf(unused + len, unused_size - len, "%s%.60s", len ? ", " : "", m->name);
	}
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
	char why[160] = "";
	for (int i = 0; i < scene->light_count && !shadow_light; i++)
		if (scene->lights[i].casts_shadow && scene->lights[i].type == AA_LIGHT_DIRECTIONAL) {
			const struct aa_light *l = &scene->lights[i];
			bool dark = l->intensity <= 0.0f || (l->color[0] <= 0.0f && l->color[1] <= 0.0f && l->color[2] <= 0.0f);
			snprintf(why, sizeof why, dark ? "lights[%d] casts shadows but gives no light (intensity or colour 0)"
						       : "lights[%d] (directional) casts shadows: up to %d cascades fitted to the view",
				 i, AA_SHADOW_CASCADES);
			shadow_light = dark ? NULL : why;
			if (dark)
				break;
		}
	plan->shadow_map = shadow_light != NULL;
	add(plan, "shadow-map", plan->shadow_map,
	    plan->shadow_map || why[0] ? "%s" : "no light casts shadows", plan->shadow_map ? shadow_light : why);

	bool metal_rough = false;
	for (int o = 0; o < scene->object_count; o++)
		metal_rough |= scene->materials[scene->objects[o].material_index].model == AA_SHADING_METAL_ROUGH;
	add(plan, "scene-forward", true, "%s", metal_rough
	    ? "forward shading, Lambert + Blinn-Phong and GGX metallic-roughness (file materials), reversed-Z float depth"
	    : "forward shading, Lambert + Blinn-Phong specular, reversed-Z float depth");

	char used[160], unused[120];
	material_use(scene, false, used, sizeof used, unused, sizeof unused);
	plan->alpha_test = aa_scene_has_cutout(scene);
	if (!plan->alpha_test && unused[0])
		snprintf(used, sizeof used, "no object draws with a cut-out material (%.100s)", unused);
	add(plan, "alpha-test", plan->alpha_test, used[0] ? "%s" : "no material is an alpha cut-out", used);
	material_use(scene, true, used, sizeof used, unused, sizeof unused);
	add(plan, "alpha-blend", used[0] != '\0', "%s", used[0] ? used : "no object draws with a blended material");

	const char *who = first_method_needing(spec, AA_NEED_VELOCITY);
	plan->velocity = who != NULL;
	if (who)
		add(plan, "velocity", true, "%s reprojects history", who);
	else if (path_moves(scene, spec->path)) {
		snprintf(why, sizeof why, "the camera moves (path '%.60s'), but no chosen method reprojects history",
			 spec->path);
		add(plan, "velocity", false, "%s", why);
	} else
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

	snprintf(why, sizeof why, "%d jittered renders accumulated in float (ground truth)",
		 spec->reference_samples);
	add(plan, "reference-accumulate", true, "%s", why);
	add(plan, "readback", true, "%s", "every output is read back for metrics and images");
}
