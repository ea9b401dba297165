/* The frame plan without a GPU: for every shipped scene and every method, exactly the
 * passes the scene's content and the method call for, in a fixed order, each with its reason. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "run/engine.h"
#include "render/frame_plan.h"
#include "methods/methods.h"
#include "run/job_spec.h"

static const char *const order[] = {"shadow-map", "scene-forward", "alpha-test", "alpha-blend", "velocity",
				    "model-ids", "history", "supersample-resolve", "reference-accumulate", "readback"};
#define PASSES ((int)(sizeof order / sizeof order[0]))

/* What each shipped scene holds, from its file: a shadow-casting directional light, a cut-out material,
 * anything that moves. */
static const struct { const char *scene; bool shadow, cutout, animated; } scenes[] = {
	{"checker-box", true, false, false},
	{"cutout-fence", true, true, false},
	{"hairball", false, false, true},
	{"hard-edges", true, false, false},
	{"hdr-teleport", false, false, true},
	{"horizon", false, false, false},
	{"moving-sphere", true, false, true},
	{"spinning-wheel", false, false, true},
	{"thin-wires", false, false, false},
	/* the hard cases (docs/hard-cases.md) */
	{"specular-aliasing", false, false, false},
	{"subpixel-specks", false, false, false},
	{"moire", false, false, false},
	{"far-from-origin", false, false, true},
	{"far-from-origin-control", false, false, true},
	{"depth-extremes", false, false, false},
	{"hdr-fireflies", false, false, false},
	{"fast-ball", false, false, true},
};

/* What each method asks for beyond the scene pass (engine/methods/, docs/methods.md). */
static const struct { const char *method; bool velocity, ids, history, supersampled; unsigned needs; } methods[] = {
	{"none", false, false, false, false, 0},
	{"ssaa", false, false, false, true, AA_NEED_SUPERSAMPLED},
	{"msaa", false, false, false, false, AA_NEED_MSAA},
	{"gbaa", false, false, false, false, AA_NEED_GBUFFER},
	{"taa", true, false, true, false, AA_NEED_VELOCITY | AA_NEED_HISTORY | AA_NEED_DEPTH},
	{"taa-sobel", true, true, true, false, AA_NEED_VELOCITY | AA_NEED_HISTORY | AA_NEED_DEPTH | AA_NEED_IDS},
	{"copy", false, false, false, false, 0},
	{"floor", false, false, false, false, 0},
	{"smaa", false, false, false, false, 0},
	{"smaa:edge=depth", false, false, false, false, AA_NEED_DEPTH},
	{"smaa:mode=t2x", true, false, true, false, AA_NEED_VELOCITY | AA_NEED_HISTORY},
	{"smaa:mode=s2x", false, false, false, false, AA_NEED_MSAA},
	{"smaa:mode=4x", true, false, true, false, AA_NEED_VELOCITY | AA_NEED_HISTORY | AA_NEED_MSAA},
	{"cmaa2", false, false, false, false, 0},
	{"fxaa", false, false, false, false, 0},
	{"fxaa-cs", false, false, false, false, 0},
	{"asaa", true, false, true, false, AA_NEED_VELOCITY | AA_NEED_HISTORY | AA_NEED_SUBSAMPLES},
	{"t2msaa", true, false, true, false, AA_NEED_VELOCITY | AA_NEED_HISTORY | AA_NEED_MSAA},
	{"rsaa", false, false, false, false, AA_NEED_GBUFFER | AA_NEED_SUBSAMPLES},
};
#define METHODS ((int)(sizeof methods / sizeof methods[0]))

static struct aa_scene *load(const char *name)
{
	char file[1024];
	struct aa_scene *sc = NULL;
	struct aa_error err = {0};
	if (aa_scene_resolve(name, file, sizeof file, &err) || aa_scene_load(file, &sc, &err))
		fail_msg("%s: %s", name, err.message);
	return sc;
}

static void spec_of(struct aa_job_spec *spec, const char *const *texts, int n)
{
	aa_job_spec_defaults(spec);
	spec->method_count = n;
	spec->reference_samples = 48;
	for (int i = 0; i < n; i++) {
		struct aa_error err = {0};
		if (aa_method_parse(texts[i], "methods", &spec->methods[i].method, &spec->methods[i].params, &err))
			fail_msg("%s: %s", texts[i], err.message);
		aa_method_label(spec->methods[i].method, &spec->methods[i].params, spec->methods[i].label,
				sizeof spec->methods[i].label);
	}
}

static const struct aa_plan_entry *entry(const struct aa_frame_plan *plan, int i, const char *pass)
{
	if (i >= plan->entry_count || strcmp(plan->entries[i].pass, pass) != 0)
		fail_msg("plan entry %d is %s, expected %s", i, i < plan->entry_count ? plan->entries[i].pass : "missing",
			 pass);
	return &plan->entries[i];
}

/* The shipped scenes and the registered methods are the ones listed above (a new one needs its line). */
static void test_scene_list(void **state)
{
	(void)state;
	for (int k = 0; k < aa_method_count; k++) {
		bool listed = false;
		for (int m = 0; m < METHODS; m++)
			listed = listed || strcmp(methods[m].method, aa_methods[k]->name) == 0;
		if (!listed)
			fail_msg("method %s has no expected plan here", aa_methods[k]->name);
	}
	char **names;
	int count;
	assert_int_equal(aa_scene_list(&names, &count), 0);
	assert_int_equal(count, (int)(sizeof scenes / sizeof scenes[0]));
	for (int i = 0; i < count; i++) {
		bool known = false;
		for (size_t k = 0; k < sizeof scenes / sizeof scenes[0]; k++)
			known = known || strcmp(names[i], scenes[k].scene) == 0;
		if (!known)
			fail_msg("scene %s has no expected plan here", names[i]);
		free(names[i]);
	}
	free(names);
}

/* Every scene with every method alone: the scene decides the shadow map and the alpha test, the method
 * decides velocity, IDs, history and supersampling; the scene pass, reference and readback always run. */
static void test_each_scene_each_method(void **state)
{
	(void)state;
	for (size_t s = 0; s < sizeof scenes / sizeof scenes[0]; s++) {
		struct aa_scene *sc = load(scenes[s].scene);
		assert_int_equal(aa_scene_has_shadow_caster_light(sc), scenes[s].shadow);
		assert_int_equal(aa_scene_has_cutout(sc), scenes[s].cutout);
		assert_int_equal(aa_scene_has_animation(sc), scenes[s].animated);
		for (int m = 0; m < METHODS; m++) {
			struct aa_job_spec spec;
			spec_of(&spec, &methods[m].method, 1);
			struct aa_frame_plan plan;
			aa_frame_plan_build(sc, &spec, &plan);
			/* no shipped scene has a blended material */
			const bool ran[PASSES] = {scenes[s].shadow, true, scenes[s].cutout, false, methods[m].velocity,
						  methods[m].ids, methods[m].history, methods[m].supersampled, true, true};
			assert_int_equal(plan.entry_count, PASSES);
			for (int i = 0; i < PASSES; i++) {
				const struct aa_plan_entry *e = entry(&plan, i, order[i]);
				if (e->ran != ran[i])
					fail_msg("%s / %s: %s %s (%s)", scenes[s].scene, methods[m].method, order[i],
						 e->ran ? "runs" : "is skipped", e->reason);
				if (!e->reason[0])
					fail_msg("%s / %s: %s has no reason", scenes[s].scene, methods[m].method, order[i]);
			}
			const bool flags[] = {plan.shadow_map, plan.alpha_test, plan.velocity, plan.ids, plan.history,
					      plan.supersampled};
			const int flag_entry[] = {0, 2, 4, 5, 6, 7};
			for (int f = 0; f < 6; f++)
				if (flags[f] != ran[flag_entry[f]])
					fail_msg("%s / %s: plan flag of %s is %d", scenes[s].scene, methods[m].method,
						 order[flag_entry[f]], flags[f]);
			if (plan.needs != methods[m].needs)
				fail_msg("%s: needs 0x%x, expected 0x%x", methods[m].method, plan.needs, methods[m].needs);
			/* a pass a method asks for names that method as the reason */
			if (methods[m].velocity && !strstr(plan.entries[4].reason, spec.methods[0].label))
				fail_msg("velocity's reason does not name %s: %s", spec.methods[0].label, plan.entries[4].reason);
		}
		aa_scene_free(sc);
	}
}

/* Several methods: the union of their needs, each pass's reason naming the first method that asks. */
static void test_methods_combine(void **state)
{
	(void)state;
	struct aa_scene *sc = load("thin-wires");
	const char *const texts[] = {"none", "fxaa", "ssaa:4", "t2msaa", "taa-sobel"};
	struct aa_job_spec spec;
	spec_of(&spec, texts, 5);
	struct aa_frame_plan plan;
	aa_frame_plan_build(sc, &spec, &plan);
	assert_int_equal(plan.needs, AA_NEED_SUPERSAMPLED | AA_NEED_VELOCITY | AA_NEED_HISTORY | AA_NEED_MSAA |
					     AA_NEED_DEPTH | AA_NEED_IDS);
	assert_string_equal(entry(&plan, 4, "velocity")->reason, "t2msaa:0.125 reprojects history");
	assert_string_equal(entry(&plan, 5, "model-ids")->reason, "taa-sobel reads model IDs");
	assert_string_equal(entry(&plan, 6, "history")->reason, "t2msaa:0.125 keeps history");
	assert_string_equal(entry(&plan, 7, "supersample-resolve")->reason,
			    "ssaa:4 renders at a higher resolution and box-filters down");
	assert_string_equal(entry(&plan, 8, "reference-accumulate")->reason,
			    "48 jittered renders accumulated in float (ground truth)");
	assert_false(entry(&plan, 0, "shadow-map")->ran);
	assert_string_equal(plan.entries[0].reason, "no light casts shadows");
	aa_scene_free(sc);

	/* a scene where things move, but no method reprojects: velocity is skipped, and says why */
	sc = load("spinning-wheel");
	const char *const plain[] = {"none", "smaa"};
	spec_of(&spec, plain, 2);
	aa_frame_plan_build(sc, &spec, &plan);
	assert_false(entry(&plan, 4, "velocity")->ran);
	assert_string_equal(plan.entries[4].reason, "objects move, but no chosen method reprojects history");
	aa_scene_free(sc);
}

/* Scenes built in code: shadows only from a directional light that casts them. */
static void test_lights(void **state)
{
	(void)state;
	struct aa_scene *sc = load("thin-wires");
	const char *const none[] = {"none"};
	struct aa_job_spec spec;
	spec_of(&spec, none, 1);
	struct aa_frame_plan plan;
	assert_true(sc->light_count >= 1);
	for (int i = 0; i < sc->light_count; i++)
		sc->lights[i].casts_shadow = false;
	aa_frame_plan_build(sc, &spec, &plan);
	assert_false(plan.shadow_map);
	sc->lights[0].casts_shadow = true;
	sc->lights[0].type = AA_LIGHT_DIRECTIONAL;
	aa_frame_plan_build(sc, &spec, &plan);
	assert_true(plan.shadow_map);
	assert_non_null(strstr(plan.entries[0].reason, "(directional) casts shadows"));
	sc->lights[0].type = AA_LIGHT_POINT;
	aa_frame_plan_build(sc, &spec, &plan);
	assert_false(plan.shadow_map);
	aa_scene_free(sc);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_scene_list),
		cmocka_unit_test(test_each_scene_each_method),
		cmocka_unit_test(test_methods_combine),
		cmocka_unit_test(test_lights),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
