/* The engine on the real Vulkan device (lavapipe here), with validation on when installed: every scene
 * with every method stays finite, the frame plan runs only what is needed, the sampled reference
 * converges to the exact coverage, supersampling beats no AA, and a stop is taken during the set-up. */
#include <math.h>
#include <stdatomic.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "run/engine.h"
#include "fixture.h"
#include "reference/exact_coverage.h"
#include "methods/methods.h"



static bool plan_ran(const struct aa_job_result *r, const char *pass)
{
	for (int i = 0; i < r->plan_count; i++)
		if (strcmp(r->plan[i].pass, pass) == 0)
			return r->plan[i].ran;
	fail_msg("pass %s is not in the plan", pass);
	return false;
}

static void test_every_scene_every_method_finite(void **state)
{
	(void)state;
	char **names;
	int count;
	assert_int_equal(aa_scene_list(&names, &count), 0);
	assert_true(count >= 4);
	const char *methods[AA_MAX_METHODS];
	for (int i = 0; i < aa_method_count; i++)
		methods[i] = aa_methods[i]->name;
	for (int s = 0; s < count; s++) {
		struct aa_job_spec spec;
		fixture_spec(&spec, names[s], methods, aa_method_count, 64, 36, 2, 4);
		struct aa_job_result *r = fixture_run(&spec, NULL, NULL, NULL);
		for (int f = 0; f < r->reference.frame_count; f++)
			assert_int_equal(r->reference.frames[f].nonfinite, 0);
		for (int m = 0; m < r->method_count; m++) {
			assert_int_equal(r->methods[m].frame_count, 2);
			for (int f = 0; f < 2; f++) {
				const struct aa_frame_result *fr = &r->methods[m].frames[f];
				if (fr->nonfinite)
					fail_msg("%s / %s frame %d: %ld NaN/Inf values", names[s], r->methods[m].label, f,
						 fr->nonfinite);
				assert_true(fr->gpu_ms > 0.0);
				assert_true(isfinite(fr->metrics.ssim));
			}
		}
		printf("  %-16s ok (%llu triangles)\n", names[s], (unsigned long long)r->scene_triangles);
		fixture_free(r);
		free(names[s]);
	}
	free(names);
}

/* A static, shadowless, unlit scene runs the scene pass, the reference and readback, and nothing else. */
static void test_plan_skips_what_is_not_needed(void **state)
{
	(void)state;
	struct aa_polygon2d polys[16];
	int n = aa_pattern2d_make(AA_PATTERN2D_HALF_PLANE, 30.0, 0, 0, 32, 32, polys);
	struct aa_scene *scene;
	struct aa_error err = {0};
	float fg[3] = {1, 1, 1}, bg[3] = {0, 0, 0};
	assert_int_equal(aa_scene_from_polygons(polys, n, 32, 32, fg, bg, &scene, &err), 0);
	const char *methods[] = {"none"};
	struct aa_job_spec spec;
	fixture_spec(&spec, "half-plane", methods, 1, 32, 32, 1, 2);
	struct aa_job_result *r = fixture_run(&spec, scene, NULL, NULL);
	assert_true(plan_ran(r, "scene-forward"));
	assert_true(plan_ran(r, "reference-accumulate"));
	const char *skipped[] = {"shadow-map", "alpha-test", "velocity", "model-ids", "history",
				 "supersample-resolve"};
	for (size_t i = 0; i < sizeof skipped / sizeof skipped[0]; i++)
		if (plan_ran(r, skipped[i]))
			fail_msg("%s ran for a static shadowless scene", skipped[i]);
	/* the method's passes are exactly its scene render: no shadow map was drawn */
	assert_int_equal(r->methods[0].frames[0].pass_count, 1);
	assert_string_equal(r->methods[0].frames[0].passes[0].name, "scene");
	fixture_free(r);
	aa_scene_free(scene);

	/* and a scene whose light casts shadows gets the shadow map, in every method's passes */
	char **names;
	int count;
	assert_int_equal(aa_scene_list(&names, &count), 0);
	bool found = false;
	for (int s = 0; s < count && !found; s++) {
		char file[1024];
		struct aa_scene *sc;
		if (aa_scene_resolve(names[s], file, sizeof file, &err) || aa_scene_load(file, &sc, &err))
			continue;
		found = aa_scene_has_shadow_caster_light(sc);
		aa_scene_free(sc);
		if (!found)
			continue;
		fixture_spec(&spec, names[s], methods, 1, 32, 18, 1, 2);
		r = fixture_run(&spec, NULL, NULL, NULL);
		assert_true(plan_ran(r, "shadow-map"));
		assert_string_equal(r->methods[0].frames[0].passes[0].name, "shadow-map");
		fixture_free(r);
	}
	for (int s = 0; s < count; s++)
		free(names[s]);
	free(names);
	assert_true(found);
}

struct capture {
	double *coverage;
	double mean_abs_error;
	double max_abs_error;
};

static int capture_reference(const struct aa_event *ev, void *user)
{
	struct capture *c = user;
	if (ev->type != AA_EVENT_REFERENCE_FRAME)
		return 0;
	const struct aa_image_rgbaf *img = ev->linear;
	size_t n = (size_t)img->width * img->height;
	double sum = 0, max = 0;
	for (size_t i = 0; i < n; i++) {
		double e = fabs(img->pixels[i * 4] - c->coverage[i]);
		sum += e;
		max = e > max ? e : max;
	}
	c->mean_abs_error = sum / (double)n;
	c->max_abs_error = max;
	return 0;
}

/* The sampled reference converges to the exact box-filtered coverage as samples grow. */
static void test_reference_converges_to_exact_coverage(void **state)
{
	(void)state;
	const int w = 48, h = 48;
	struct {
		enum aa_pattern2d_kind kind;
		double angle, thickness;
		int spokes;
		const char *name;
	} patterns[] = {
		{AA_PATTERN2D_HALF_PLANE, 30.0, 0, 0, "half-plane 30deg"},
		{AA_PATTERN2D_HALF_PLANE, 3.0, 0, 0, "half-plane 3deg"},
		{AA_PATTERN2D_BAR, 20.0, 0.5, 0, "bar 0.5px 20deg"},
		{AA_PATTERN2D_STAR, 7.0, 0, 12, "star of 12 wedges"},
	};
	const int sample_counts[] = {4, 16, 64, 256};
	for (size_t p = 0; p < sizeof patterns / sizeof patterns[0]; p++) {
		struct aa_polygon2d polys[16];
		int n = aa_pattern2d_make(patterns[p].kind, patterns[p].angle, patterns[p].thickness,
					  patterns[p].spokes, w, h, polys);
		struct capture c = {.coverage = calloc((size_t)w * h, sizeof(double))};
		aa_exact_coverage(polys, n, w, h, c.coverage);
		struct aa_scene *scene;
		struct aa_error err = {0};
		float fg[3] = {1, 1, 1}, bg[3] = {0, 0, 0};
		assert_int_equal(aa_scene_from_polygons(polys, n, w, h, fg, bg, &scene, &err), 0);
		double errors[4];
		printf("  %-18s", patterns[p].name);
		for (int k = 0; k < 4; k++) {
			const char *methods[] = {"none"};
			struct aa_job_spec spec;
			fixture_spec(&spec, patterns[p].name, methods, 1, w, h, 1, sample_counts[k]);
			fixture_free(fixture_run(&spec, scene, capture_reference, &c));
			errors[k] = c.mean_abs_error;
			printf("  N=%-3d %.5f", sample_counts[k], errors[k]);
		}
		printf("\n");
		/* error falls as samples grow (roughly 1/N for stratified low-discrepancy points) */
		for (int k = 1; k < 4; k++)
			if (!(errors[k] < errors[k - 1] * 0.8))
				fail_msg("%s: error did not fall from N=%d (%g) to N=%d (%g)", patterns[p].name,
					 sample_counts[k - 1], errors[k - 1], sample_counts[k], errors[k]);
		assert_true(errors[3] < 0.005);
		aa_scene_free(scene);
		free(c.coverage);
	}
}

/* Supersampling beats one sample per pixel against the reference on thin geometry. */
static void test_ssaa_beats_none(void **state)
{
	(void)state;
	const char *methods[] = {"none", "ssaa:16"};
	struct aa_job_spec spec;
	fixture_spec(&spec, "thin-wires", methods, 2, 160, 90, 1, 32);
	struct aa_job_result *r = fixture_run(&spec, NULL, NULL, NULL);
	double none = r->methods[0].frames[0].metrics.psnr, ssaa = r->methods[1].frames[0].metrics.psnr;
	printf("  thin-wires 160x90: none %.2f dB, ssaa:16 %.2f dB, convergence %.2f dB\n", none, ssaa,
	       r->reference.frames[0].convergence_psnr);
	assert_true(ssaa > none + 3.0);
	assert_true(r->methods[1].memory_bytes > r->methods[0].memory_bytes);
	fixture_free(r);
}

static int hash_frames(const struct aa_event *ev, void *user)
{
	uint64_t *h = user;
	if (ev->type == AA_EVENT_METHOD_FRAME)
		for (size_t i = 0; i < (size_t)ev->image->width * ev->image->height * 4; i++)
			*h = (*h ^ ev->image->pixels[i]) * 1099511628211ull;
	return 0;
}

/* A second job on the same loaded scene finds it already on the GPU, and renders the same images. */
static void test_uploaded_scene_is_reused(void **state)
{
	(void)state;
	char file[1024];
	struct aa_error err = {0};
	struct aa_scene *scene;
	assert_int_equal(aa_scene_resolve("moving-sphere", file, sizeof file, &err), 0);
	assert_int_equal(aa_scene_load(file, &scene, &err), 0);
	const char *methods[] = {"none", "msaa:4"};
	struct aa_job_spec spec;
	fixture_spec(&spec, "moving-sphere", methods, 2, 64, 36, 2, 2);
	struct aa_upload_stats before = aa_engine_upload_stats(fixture_engine);
	uint64_t h1 = 14695981039346656037ull, h2 = h1;
	fixture_free(fixture_run(&spec, scene, hash_frames, &h1));
	fixture_free(fixture_run(&spec, scene, hash_frames, &h2));
	struct aa_upload_stats after = aa_engine_upload_stats(fixture_engine);
	printf("  uploads: %llu misses, %llu hits, %llu bytes cached\n",
	       (unsigned long long)(after.misses - before.misses), (unsigned long long)(after.hits - before.hits),
	       (unsigned long long)after.bytes);
	assert_int_equal(after.misses - before.misses, 1);
	assert_int_equal(after.hits - before.hits, 1);
	assert_true(after.bytes > 0);
	assert_true(h1 == h2);
	/* a tiny budget keeps only the scene in use */
	aa_engine_set_upload_budget(fixture_engine, 1);
	fixture_free(fixture_run(&spec, scene, NULL, NULL));
	assert_int_equal(aa_engine_upload_stats(fixture_engine).scenes, 1);
	aa_engine_set_upload_budget(fixture_engine, 256ull << 20);
	aa_scene_free(scene);
}

static int count_events(const struct aa_event *ev, void *user)
{
	int *counts = user;
	counts[ev->type]++;
	return 0;
}

/* A stop asked before a job's set-up ends it there: cancelled before any upload or event, and the next
 * job on the engine runs. */
static void test_stop_during_set_up(void **state)
{
	(void)state;
	const char *methods[] = {"none", "msaa:4"};
	struct aa_job_spec spec;
	fixture_spec(&spec, "moving-sphere", methods, 2, 64, 36, 2, 2);
	atomic_int stop = 1;
	aa_engine_set_interrupt(fixture_engine, &stop);
	struct aa_upload_stats before = aa_engine_upload_stats(fixture_engine);
	int counts[AA_EVENT_REFERENCE_KEY + 1] = {0};
	struct aa_job_result *r = NULL, *r_missing = NULL;
	struct aa_error err = {0}, err_missing = {0};
	const int rc = aa_job_run(fixture_engine, &spec, count_events, counts, &r, &err);
	struct aa_upload_stats after = aa_engine_upload_stats(fixture_engine);
	/* before the scene is even looked up: a stopped job names no missing scene */
	struct aa_job_spec missing = spec;
	snprintf(missing.scene, sizeof missing.scene, "no-such-scene");
	const int rc_missing = aa_job_run(fixture_engine, &missing, NULL, NULL, &r_missing, &err_missing);
	aa_engine_set_interrupt(fixture_engine, NULL);
	if (r)
		fixture_free(r);
	if (r_missing)
		fixture_free(r_missing);
	assert_int_not_equal(rc, 0);
	assert_int_equal(err.code, AA_ERR_CANCELLED);
	assert_int_equal(counts[AA_EVENT_JOB_STARTED], 0);
	assert_int_equal(after.misses + after.hits, before.misses + before.hits);
	assert_int_not_equal(rc_missing, 0);
	assert_int_equal(err_missing.code, AA_ERR_CANCELLED);
	stop = 0;
	aa_engine_set_interrupt(fixture_engine, &stop);
	fixture_free(fixture_run(&spec, NULL, NULL, NULL));
	aa_engine_set_interrupt(fixture_engine, NULL);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_plan_skips_what_is_not_needed),
		cmocka_unit_test(test_reference_converges_to_exact_coverage),
		cmocka_unit_test(test_ssaa_beats_none),
		cmocka_unit_test(test_every_scene_every_method_finite),
		cmocka_unit_test(test_uploaded_scene_is_reused),
		cmocka_unit_test(test_stop_during_set_up),
	};
	return fixture_status(cmocka_run_group_tests(tests, fixture_setup, fixture_teardown));
}
