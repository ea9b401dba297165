/* The FLIP reference side made once and shared: aa_flip_ldr_*_against gives the one-shot map to the bit,
 * for several image pairs, sizes, ppd and thread counts; and the per-frame scorer, which makes it once per
 * frame and scores methods on two threads, gives each method the metrics and FLIP image it gets alone. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "metrics/flip.h"
#include "metrics/metrics.h"
#include "run/frame_scoring.h"

#include "flip_images.h"

static void to_linear(const struct aa_image_rgba8 *in, struct aa_image_rgbaf *out)
{
	assert_int_equal(aa_image_rgbaf_alloc(out, in->width, in->height), 0);
	for (size_t i = 0; i < (size_t)in->width * in->height * 4; i++)
		out->pixels[i] = (float)in->pixels[i] / 255.0f * 1.25f - 0.1f; /* some values outside [0,1] */
}

/* One reference, several tests: each shared map equals the one-shot map, bit for bit. */
static void check_shared(int w, int h, float ppd, int threads)
{
	struct aa_image_rgba8 ref, test[3];
	struct aa_image_rgbaf reff, testf;
	make_image(&ref, w, h, 1, 0);
	make_image(&test[0], w, h, 2, 30);
	make_image(&test[1], w, h, 7, 3);
	make_image(&test[2], w, h, 1, 0); /* the reference itself: a map of zeros */
	to_linear(&ref, &reff);
	const size_t n = (size_t)w * h;
	float *a = malloc(n * sizeof *a), *b = malloc(n * sizeof *b);
	assert_non_null(a);
	assert_non_null(b);
	const struct aa_flip_options opt = { .ppd = ppd, .threads = threads };
	struct aa_flip_reference *shared = NULL, *sharedf = NULL;
	assert_int_equal(aa_flip_reference_rgba8(&ref, &opt, &shared, NULL), 0);
	assert_int_equal(aa_flip_reference_linear(&reff, &opt, &sharedf, NULL), 0);
	for (int t = 0; t < 3; t++) {
		memset(a, 0xa5, n * sizeof *a);
		memset(b, 0x5a, n * sizeof *b);
		assert_int_equal(aa_flip_ldr_rgba8(&ref, &test[t], &opt, a, NULL), 0);
		assert_int_equal(aa_flip_ldr_rgba8_against(shared, &test[t], &opt, b, NULL), 0);
		assert_memory_equal(a, b, n * sizeof *a);
		to_linear(&test[t], &testf);
		assert_int_equal(aa_flip_ldr_linear(&reff, &testf, &opt, a, NULL), 0);
		assert_int_equal(aa_flip_ldr_linear_against(sharedf, &testf, NULL, b, NULL), 0);
		assert_memory_equal(a, b, n * sizeof *a);
		aa_image_rgbaf_free(&testf);
	}
	aa_flip_reference_free(shared);
	aa_flip_reference_free(sharedf);
	free(a);
	free(b);
	aa_image_rgba8_free(&ref);
	aa_image_rgbaf_free(&reff);
	for (int t = 0; t < 3; t++)
		aa_image_rgba8_free(&test[t]);
}

static void test_shared_equals_one_shot(void **state)
{
	(void)state;
	check_shared(1, 1, 0.0f, 0);
	check_shared(37, 23, 0.0f, 1);
	check_shared(37, 23, 0.0f, 3);
	check_shared(3, 50, 0.0f, 2);
	check_shared(1100, 9, 0.0f, 2);  /* more than one strip of columns, a partial last block */
	check_shared(300, 200, 0.0f, 5); /* bands of rows on several threads */
	check_shared(64, 40, 10.0f, 2);
	check_shared(70, 33, 150.0f, 2);
}

/* One reference remade for image after image, at the same size (its memory kept) and at another. */
static void test_remade(void **state)
{
	(void)state;
	struct aa_flip_reference *shared = NULL;
	const int sizes[][2] = { { 90, 40 }, { 90, 40 }, { 33, 70 }, { 90, 40 } };
	for (int k = 0; k < 4; k++) {
		const int w = sizes[k][0], h = sizes[k][1];
		struct aa_image_rgba8 ref, test;
		make_image(&ref, w, h, 11 + (uint32_t)k, 20 * (k % 2));
		make_image(&test, w, h, 5, 9);
		float *a = malloc((size_t)w * h * sizeof *a), *b = malloc((size_t)w * h * sizeof *b);
		assert_int_equal(aa_flip_reference_rgba8(&ref, NULL, &shared, NULL), 0);
		assert_int_equal(aa_flip_ldr_rgba8(&ref, &test, NULL, a, NULL), 0);
		assert_int_equal(aa_flip_ldr_rgba8_against(shared, &test, NULL, b, NULL), 0);
		assert_memory_equal(a, b, (size_t)w * h * sizeof *a);
		free(a);
		free(b);
		aa_image_rgba8_free(&ref);
		aa_image_rgba8_free(&test);
	}
	aa_flip_reference_free(shared);
}

static void test_shared_errors(void **state)
{
	(void)state;
	struct aa_image_rgba8 ref, small;
	make_image(&ref, 20, 10, 1, 0);
	make_image(&small, 10, 10, 1, 0);
	struct aa_flip_reference *shared = NULL;
	assert_int_equal(aa_flip_reference_rgba8(&ref, NULL, &shared, NULL), 0);
	float map[200];
	struct aa_error err = { 0 };
	assert_int_equal(aa_flip_ldr_rgba8_against(shared, &small, NULL, map, &err), -1);
	const struct aa_flip_options other_ppd = { .ppd = 30.0f };
	assert_int_equal(aa_flip_ldr_rgba8_against(shared, &ref, &other_ppd, map, &err), -1);
	assert_int_equal(aa_flip_ldr_rgba8_against(NULL, &ref, NULL, map, &err), -1);
	struct aa_flip_reference *none = NULL;
	const struct aa_flip_options bad_ppd = { .ppd = -1.0f };
	assert_int_equal(aa_flip_reference_rgba8(&ref, &bad_ppd, &none, &err), -1);
	assert_null(none);
	aa_flip_reference_free(shared);
	aa_flip_reference_free(NULL);
	aa_image_rgba8_free(&ref);
	aa_image_rgba8_free(&small);
}

/* ------------------------------------------------------------------------------- the per-frame scorer */

enum { W = 160, H = 90, FRAMES = 3, METHODS = 4 };

struct captured {
	struct aa_image_rgba8 flip8[FRAMES][METHODS];
	int seen;
};

static int on_event(const struct aa_event *ev, void *user)
{
	struct captured *c = user;
	if (ev->type != AA_EVENT_METHOD_FRAME)
		return 0;
	struct aa_image_rgba8 *dst = &c->flip8[ev->frame_ordinal][ev->method_index];
	assert_int_equal(aa_image_rgba8_alloc(dst, W, H), 0);
	memcpy(dst->pixels, ev->flip_map->pixels, (size_t)W * H * 4);
	c->seen++;
	return 0;
}

/* Method i's output at frame k: shapes with noise of its own (method 0 is the reference, so exact); the
 * reference differs from frame to frame. */
static void method_output(int k, int i, struct aa_image_rgbaf *out)
{
	struct aa_image_rgba8 img;
	make_image(&img, W, H, 1 + (uint32_t)k + 100 * (uint32_t)i, 2 * k + 4 * i);
	for (size_t p = 0; p < (size_t)W * H * 4; p++)
		out->pixels[p] = (float)img.pixels[p] / 255.0f;
	aa_image_rgba8_free(&img);
}

static void run_scorer(bool inline_scoring)
{
	static struct aa_job_result result; /* large: not on the stack */
	memset(&result, 0, sizeof result);
	struct aa_job_spec *spec = &result.spec;
	spec->width = W;
	spec->height = H;
	spec->frames = FRAMES;
	spec->method_count = METHODS;
	spec->timing_repeat = 1;
	spec->over_threshold = 0.02;
	result.method_count = METHODS;
	for (int i = 0; i < METHODS; i++) {
		snprintf(spec->methods[i].label, sizeof spec->methods[i].label, "m%d", i);
		result.methods[i].frames = calloc(FRAMES, sizeof *result.methods[i].frames);
		assert_non_null(result.methods[i].frames);
	}
	struct captured cap = { 0 };
	struct aa_scoring *sc = NULL;
	struct aa_error err = { 0 };
	assert_int_equal(aa_scoring_create(spec, &result, on_event, &cap, inline_scoring, &sc, &err), 0);
	for (int k = 0; k < FRAMES; k++) {
		/* as a job does: the slot to fill is free once the scoring before has ended */
		assert_int_equal(aa_scoring_wait(sc, &err), 0);
		struct aa_scoring_frame *f = aa_scoring_next(sc);
		f->ordinal = f->frame = k;
		method_output(k, 0, &f->full);
		aa_image_encode_srgb8(&f->full, &f->ref8);
		for (int i = 0; i < METHODS; i++) {
			method_output(k, i, &f->outputs[i]);
			f->order[i] = (i + k) % METHODS; /* the order rotates, as a job's does */
		}
		assert_int_equal(aa_scoring_submit(sc, f, &err), 0);
	}
	assert_int_equal(aa_scoring_wait(sc, &err), 0);
	aa_scoring_destroy(sc);
	assert_int_equal(cap.seen, FRAMES * METHODS);

	/* Each method alone, one shot, against its reference. */
	struct aa_image_rgbaf full, out;
	struct aa_image_rgba8 ref8, out8, flip8;
	assert_int_equal(aa_image_rgbaf_alloc(&full, W, H), 0);
	assert_int_equal(aa_image_rgbaf_alloc(&out, W, H), 0);
	assert_int_equal(aa_image_rgba8_alloc(&ref8, W, H), 0);
	assert_int_equal(aa_image_rgba8_alloc(&out8, W, H), 0);
	assert_int_equal(aa_image_rgba8_alloc(&flip8, W, H), 0);
	for (int k = 0; k < FRAMES; k++) {
		method_output(k, 0, &full);
		aa_image_encode_srgb8(&full, &ref8);
		for (int i = 0; i < METHODS; i++) {
			method_output(k, i, &out);
			aa_image_encode_srgb8(&out, &out8);
			struct aa_metrics alone;
			assert_int_equal(aa_metrics_compare(&ref8, &out8, &alone, NULL), 0);
			assert_int_equal(aa_metrics_perceptual(&ref8, &out8, &alone, &flip8, NULL), 0);
			const struct aa_metrics *scored = &result.methods[i].frames[k].metrics;
			/* bit for bit, NaN included (an exact method's PSNR) */
			assert_memory_equal(&scored->flip_mean, &alone.flip_mean, sizeof alone.flip_mean);
			assert_memory_equal(scored->fourier, alone.fourier, sizeof alone.fourier);
			assert_memory_equal(&scored->ssim, &alone.ssim, sizeof alone.ssim);
			assert_memory_equal(&scored->mse, &alone.mse, sizeof alone.mse);
			assert_memory_equal(cap.flip8[k][i].pixels, flip8.pixels, (size_t)W * H * 4);
			assert_true(i == 0 ? alone.flip_mean == 0.0 : alone.flip_mean > 0.0);
			aa_image_rgba8_free(&cap.flip8[k][i]);
		}
	}
	aa_image_rgbaf_free(&full);
	aa_image_rgbaf_free(&out);
	aa_image_rgba8_free(&ref8);
	aa_image_rgba8_free(&out8);
	aa_image_rgba8_free(&flip8);
	for (int i = 0; i < METHODS; i++)
		free(result.methods[i].frames);
}

static void test_scorer_equals_methods_alone(void **state)
{
	(void)state;
	run_scorer(false); /* on the scorer thread and its helper */
	run_scorer(true);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_shared_equals_one_shot),
		cmocka_unit_test(test_remade),
		cmocka_unit_test(test_shared_errors),
		cmocka_unit_test(test_scorer_equals_methods_alone),
	};
	return cmocka_run_group_tests_name("flip_shared", tests, NULL, NULL);
}
