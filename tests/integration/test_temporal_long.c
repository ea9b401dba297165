/* The temporal methods over long runs and in motion: 128 still frames, past the running-average
 * ramps (TAA's n/(n+1) stays below feedback_max 0.97 until frame 33 and below 0.99 until frame 99; ASAA's
 * and T2MSAA's sample counts), so that their defaults (feedback, sample caps, jitter) decide the numbers; a steady pan where reprojection must follow the motion the
 * right way; a camera cut that must look like a fresh start for several frames, not just the first.
 * Numbers without an exact answer are pinned in tests/golden/temporal.tsv (`make update-golden`). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "run/engine.h"
#include "fixture.h"
#include "golden.h"

#define TOL_PSNR 0.05    /* dB */
#define TOL_FLICKER 0.02 /* 8-bit levels */

/* seed 001's resolve counts frames since the reset itself (its running-average ramp): a cut must reset
 * that count too */
static const char *const temporal[] = {"taa", "taa-sobel", "asaa", "t2msaa", "taa:preset=seed001"};
#define TEMPORAL 5

static struct aa_job_result *run(const char *scene, const char *path, const char *const *methods, int n, int w,
				 int h, int first, int frames, int samples, const struct aa_scene *sc,
				 aa_event_fn fn, void *user)
{
	struct aa_job_spec spec;
	fixture_spec(&spec, scene, methods, n, w, h, frames, samples);
	snprintf(spec.path, sizeof spec.path, "%s", path);
	spec.first_frame = first;
	return fixture_run(&spec, sc, fn, user);
}

static double mean_psnr(const struct aa_method_result *m, int from, int to)
{
	double mse = 0;
	for (int f = from; f < to; f++)
		mse += m->frames[f].metrics.mse;
	return aa_psnr_from_mse(mse / (to - from), 255.0);
}

static double mean_flicker(const struct aa_method_result *m, int from, int to)
{
	double sum = 0;
	for (int f = from; f < to; f++)
		sum += m->frames[f].flicker;
	return sum / (to - from);
}

/* 128 frames of a still camera over a still scene: frames 112..127 are past every ramp. Their quality and
 * frame-to-frame flicker are pinned (and frames 16..31, inside the ramps), and each method must beat no
 * AA there by a margin. */
static void test_still_128_frames(void **state)
{
	(void)state;
	/* taa's production preset keeps current_weight on the current frame for good and seed 001's resolve
	 * feedback_max's weight on history, so their numbers pin those defaults */
	const char *methods[] = {"none", "taa", "taa-sobel", "asaa", "t2msaa", "taa:preset=seed001"};
	const int frames = 128, late_from = 112, count = sizeof methods / sizeof methods[0];
	struct aa_job_result *r = run("thin-wires", "static", methods, count, 64, 36, 0, frames, 16, NULL, NULL, NULL);
	char key[160];
	double none = mean_psnr(&r->methods[0], late_from, frames);
	for (int m = 1; m < count; m++) {
		double early = mean_psnr(&r->methods[m], 16, 32), late = mean_psnr(&r->methods[m], late_from, frames);
		double flicker = mean_flicker(&r->methods[m], late_from, frames);
		printf("  still thin-wires 64x36: %-18s frames 16-31 %.2f dB, 112-127 %.2f dB (none %.2f), flicker %.3f\n",
		       methods[m], early, late, none, flicker);
		assert_true(late > none + 1.0);
		snprintf(key, sizeof key, "still %s psnr_112_127", methods[m]);
		golden_check(key, late, TOL_PSNR);
		snprintf(key, sizeof key, "still %s psnr_16_31", methods[m]);
		golden_check(key, early, TOL_PSNR);
		snprintf(key, sizeof key, "still %s flicker_112_127", methods[m]);
		golden_check(key, flicker, TOL_FLICKER);
		for (int f = 0; f < frames; f++)
			assert_int_equal(r->methods[m].frames[f].nonfinite, 0);
	}
	/* the reference of a still camera over a still scene is rendered once */
	for (int f = 1; f < frames; f++)
		assert_true(r->reference.frames[f].reused);
	fixture_free(r);
}

/* A steady pan of about a pixel a frame: reprojection must fetch history from where the content was.
 * Every temporal method beats no AA on the moving image, by a pinned amount. */
static void test_pan_follows_motion(void **state)
{
	(void)state;
	char file[1024];
	struct aa_error err = {0};
	struct aa_scene *scene;
	assert_int_equal(aa_scene_resolve("thin-wires", file, sizeof file, &err), 0);
	assert_int_equal(aa_scene_load(file, &scene, &err), 0);
	scene->paths[0].kind = AA_PATH_PAN;
	scene->paths[0].degrees = -60.0f; /* half a degree a frame: about 0.6 px at 64 px over 50 degrees */
	scene->paths[0].duration = 4.0;
	const char *methods[] = {"none", "taa", "taa-sobel", "asaa", "t2msaa"};
	struct aa_job_result *r = run("thin-wires-pan", "default", methods, 5, 64, 36, 0, 24, 16, scene, NULL, NULL);
	double none = mean_psnr(&r->methods[0], 12, 24);
	char key[160];
	for (int m = 1; m < 5; m++) {
		double p = mean_psnr(&r->methods[m], 12, 24);
		printf("  pan thin-wires 64x36 frames 12-23: %-9s %.2f dB (none %.2f)\n", methods[m], p, none);
		snprintf(key, sizeof key, "pan %s psnr_12_23", methods[m]);
		golden_check(key, p, TOL_PSNR);
		snprintf(key, sizeof key, "pan %s flicker_12_23", methods[m]);
		golden_check(key, mean_flicker(&r->methods[m], 12, 24), TOL_FLICKER);
	}
	fixture_free(r);

	/* objects moving under a still camera: the sphere of moving-sphere rolls and bobs */
	const char *taa[] = {"none", "taa", "taa-sobel", "asaa", "t2msaa", "taa:preset=seed001"};
	r = run("moving-sphere", "still", taa, 6, 64, 36, 0, 16, 16, NULL, NULL, NULL);
	for (int m = 1; m < 6; m++) {
		snprintf(key, sizeof key, "moving-sphere %s psnr_8_15", taa[m]);
		golden_check(key, mean_psnr(&r->methods[m], 8, 16), TOL_PSNR);
	}
	fixture_free(r);
	aa_scene_free(scene);

	/* past a whole jitter cycle (16 frames) a still pixel of taa is settled: where the sphere comes onto
	 * it later, its own sample changes and it must start over at once (frames 32..47) */
	const char *settled[] = {"none", "taa"};
	r = run("moving-sphere", "still", settled, 2, 64, 36, 0, 48, 16, NULL, NULL, NULL);
	double late = mean_psnr(&r->methods[1], 32, 48);
	printf("  moving-sphere 64x36 frames 32-47: taa %.2f dB (none %.2f)\n", late, mean_psnr(&r->methods[0], 32, 48));
	golden_check("moving-sphere taa psnr_32_47", late, TOL_PSNR);
	fixture_free(r);
}

/* Keeps every method's 8-bit output of every frame. */
struct frames {
	int methods, w, h;
	uint8_t *pixels;
};

static int keep(const struct aa_event *ev, void *user)
{
	struct frames *f = user;
	if (ev->type == AA_EVENT_METHOD_FRAME) {
		size_t size = (size_t)f->w * f->h * 4;
		memcpy(f->pixels + ((size_t)ev->frame_ordinal * f->methods + ev->method_index) * size, ev->image->pixels,
		       size);
	}
	return 0;
}

/* A camera cut resets history: the frames after the cut equal, to a level, a fresh start at the cut, for
 * as long as it takes every ramp to matter (four frames), not only the first. */
static void test_cut_is_a_fresh_start(void **state)
{
	(void)state;
	/* thin-wires' "fly" path cuts at t = 3 s, frame 90 at 30 fps */
	const int w = 64, h = 36, after = 4;
	const size_t size = (size_t)w * h * 4;
	struct frames across = {TEMPORAL, w, h, calloc((size_t)(4 + after) * TEMPORAL, size)};
	struct frames fresh = {TEMPORAL, w, h, calloc((size_t)after * TEMPORAL, size)};
	fixture_free(run("thin-wires", "fly", temporal, TEMPORAL, w, h, 86, 4 + after, 2, NULL, keep, &across));
	fixture_free(run("thin-wires", "fly", temporal, TEMPORAL, w, h, 90, after, 2, NULL, keep, &fresh));
	for (int m = 0; m < TEMPORAL; m++)
		for (int k = 0; k < after; k++) {
			const uint8_t *a = across.pixels + ((size_t)(4 + k) * TEMPORAL + m) * size;
			const uint8_t *b = fresh.pixels + ((size_t)k * TEMPORAL + m) * size;
			int max = 0;
			for (size_t i = 0; i < size; i++)
				max = abs(a[i] - b[i]) > max ? abs(a[i] - b[i]) : max;
			if (max > 1)
				fail_msg("%s, frame %d after the cut: differs from a fresh start by %d levels", temporal[m],
					 k, max);
		}
	free(across.pixels);
	free(fresh.pixels);
}

/* A rule across two parameters: feedback_min may not exceed feedback_max (equal is a fixed weight). The job
 * is refused naming feedback_min and both values; nothing is rendered. */
static void test_feedback_order(void **state)
{
	(void)state;
	const char *const refused[] = {"taa:preset=accumulate,feedback_min=0.95,feedback_max=0.9",
				       "taa-sobel:preset=seed001,feedback_min=0.5,feedback_max=0.4"};
	for (int k = 0; k < 2; k++) {
		struct aa_job_spec spec;
		fixture_spec(&spec, "thin-wires", &refused[k], 1, 16, 9, 1, 2);
		struct aa_job_result *r = NULL;
		struct aa_error err = {0};
		assert_int_equal(aa_job_run_scene(fixture_engine, &spec, NULL, NULL, NULL, &r, &err), -1);
		assert_null(r);
		if (err.code != AA_ERR_INVALID || strcmp(err.path, "params.feedback_min") != 0 ||
		    !strstr(err.message, "must not exceed"))
			fail_msg("%s: error %d at '%s': %s", refused[k], err.code, err.path, err.message);
	}
	const char *const equal[] = {"taa:preset=accumulate,feedback_min=0.9,feedback_max=0.9"};
	struct aa_job_spec spec;
	fixture_spec(&spec, "thin-wires", equal, 1, 16, 9, 1, 2);
	fixture_free(fixture_run(&spec, NULL, NULL, NULL));
}

static void test_golden_file(void **state)
{
	(void)state;
	golden_finish();
}

static int setup(void **state)
{
	golden_open("temporal.tsv");
	return fixture_setup(state);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_still_128_frames),
		cmocka_unit_test(test_pan_follows_motion),
		cmocka_unit_test(test_cut_is_a_fresh_start),
		cmocka_unit_test(test_feedback_order),
		cmocka_unit_test(test_golden_file),
	};
	return fixture_status(cmocka_run_group_tests(tests, setup, fixture_teardown));
}
