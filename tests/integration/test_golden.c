/* Pinned quality: every method (defaults, plus variants that take other code paths) on every
 * shipped scene at a small fixed size, its PSNR (dB, from the mean MSE over the frames), SSIM and FLIP
 * against the reference, and each scene's reference itself (mean linear colour, convergence), compared with
 * tests/golden/quality.tsv. None of these numbers has an exact answer; they are pinned so that any change
 * that moves them (a search step, a jitter, a blend weight, a sample count) fails here and is either fixed
 * or accepted on purpose with `make update-golden`, which shows the diff first. Exact answers are tested
 * where they exist: a flat scene's reference is its fill colour, exactly. */
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
#include "reference/exact_coverage.h"
#include "methods/methods.h"
#include "results/results.h"

#define WIDTH 96
#define HEIGHT 54
#define FRAMES 3
#define REFERENCE_SAMPLES 16

/* Tolerances: a tenth of the smallest difference worth noticing, wide enough for rounding differences
 * between CPUs (llvmpipe's code depends on the host's vector units). */
#define TOL_PSNR 0.05   /* dB */
#define TOL_SSIM 0.0005
#define TOL_FLIP 0.0005
#define TOL_MEAN 0.0002 /* linear colour, 0..1 */

/* Besides every method's defaults: variants that run other code (other presets, paths, modes). */
static const char *const variants[] = {
	"ssaa:4", "msaa:2", "msaa:8", "msaa:4,path=virtual", "fxaa:preset=39", "fxaa:preset=20",
	"fxaa-cs:preset=29", "smaa:preset=low", "smaa:preset=ultra", "smaa:edge=color", "smaa:edge=depth",
	"rsaa:4", "rsaa:auth=0", "rsaa:auth=2", "rsaa:similarity=depth", "taa:sharpen=normalized",
	"taa-sobel:jitter_length=8", "asaa:prime=false", "t2msaa:0.25",
};

struct reference_capture {
	double mean[FRAMES][3];
};

static int capture_reference(const struct aa_event *ev, void *user)
{
	struct reference_capture *c = user;
	if (ev->type != AA_EVENT_REFERENCE_FRAME || ev->frame_ordinal >= FRAMES)
		return 0;
	const struct aa_image_rgbaf *img = ev->linear;
	size_t n = (size_t)img->width * img->height;
	double sum[3] = {0, 0, 0};
	for (size_t i = 0; i < n; i++)
		for (int k = 0; k < 3; k++)
			sum[k] += img->pixels[i * 4 + k];
	for (int k = 0; k < 3; k++)
		c->mean[ev->frame_ordinal][k] = sum[k] / (double)n;
	return 0;
}

static void check_methods(const char *scene, const struct aa_job_result *r)
{
	char key[160];
	for (int m = 0; m < r->method_count; m++) {
		const struct aa_method_result *mr = &r->methods[m];
		struct aa_method_summary s;
		aa_method_summarize(mr, &s);
		double flip = 0;
		for (int f = 0; f < mr->frame_count; f++)
			flip += mr->frames[f].metrics.flip_mean;
		flip /= mr->frame_count;
		assert_int_equal(mr->frame_count, FRAMES);
		/* a frame's GPU time is, by definition, the sum of its passes' */
		for (int f = 0; f < mr->frame_count; f++) {
			const struct aa_frame_result *fr = &mr->frames[f];
			double sum = 0;
			assert_true(fr->pass_count >= 1 && fr->pass_count <= AA_MAX_PASSES);
			for (int p = 0; p < fr->pass_count; p++) {
				assert_true(fr->passes[p].gpu_ms >= 0 && fr->passes[p].name[0]);
				sum += fr->passes[p].gpu_ms;
			}
			if (fabs(fr->gpu_ms - sum) > 1e-9 * fmax(1.0, sum))
				fail_msg("%s %s frame %d: gpu_ms %.9f, its passes sum to %.9f", scene, mr->label, f, fr->gpu_ms,
					 sum);
		}
		snprintf(key, sizeof key, "%s %s psnr", scene, mr->label);
		golden_check(key, s.psnr_mean, TOL_PSNR);
		snprintf(key, sizeof key, "%s %s ssim", scene, mr->label);
		golden_check(key, s.ssim_mean, TOL_SSIM);
		snprintf(key, sizeof key, "%s %s flip", scene, mr->label);
		golden_check(key, flip, TOL_FLIP);
	}
}

/* Runs `labels` (at most AA_MAX_METHODS at a time) on a scene and pins their numbers; the first job also
 * pins the reference. */
static void run_scene(const char *scene, const char *const *labels, int n)
{
	for (int first = 0; first < n; first += AA_MAX_METHODS) {
		int count = n - first < AA_MAX_METHODS ? n - first : AA_MAX_METHODS;
		struct aa_job_spec spec;
		fixture_spec(&spec, scene, labels + first, count, WIDTH, HEIGHT, FRAMES, REFERENCE_SAMPLES);
		struct reference_capture c;
		struct aa_job_result *r = fixture_run(&spec, NULL, capture_reference, &c);
		if (first == 0) {
			char key[160];
			for (int f = 0; f < FRAMES; f += FRAMES - 1)
				for (int k = 0; k < 3; k++) {
					snprintf(key, sizeof key, "%s reference frame%d mean_%c", scene, f, "rgb"[k]);
					golden_check(key, c.mean[f][k], TOL_MEAN);
				}
			snprintf(key, sizeof key, "%s reference convergence_psnr", scene);
			golden_check(key, r->reference.frames[0].convergence_psnr, TOL_PSNR);
		}
		check_methods(scene, r);
		fixture_free(r);
	}
}

static void test_every_scene_every_method(void **state)
{
	(void)state;
	golden_open("quality.tsv");
	const char *labels[64];
	int n = 0;
	for (int i = 0; i < aa_method_count; i++)
		labels[n++] = aa_methods[i]->name;
	for (size_t i = 0; i < sizeof variants / sizeof variants[0]; i++)
		labels[n++] = variants[i];
	char **names;
	int count;
	assert_int_equal(aa_scene_list(&names, &count), 0);
	for (int s = 0; s < count; s++) {
		run_scene(names[s], labels, n);
		free(names[s]);
	}
	free(names);
	golden_finish();
}

struct flat_capture {
	int frames;
	float worst;     /* largest |reference - fill| over pixels and channels */
	double psnr[4];  /* none's PSNR: identical is NAN */
	bool identical[4];
};

static int capture_flat(const struct aa_event *ev, void *user)
{
	struct flat_capture *c = user;
	if (ev->type != AA_EVENT_REFERENCE_FRAME)
		return 0;
	const struct aa_image_rgbaf *img = ev->linear;
	const float fill[3] = {0.25f, 0.5f, 0.125f};
	for (size_t i = 0; i < (size_t)img->width * img->height; i++)
		for (int k = 0; k < 3; k++) {
			float d = fabsf(img->pixels[i * 4 + k] - fill[k]);
			c->worst = d > c->worst ? d : c->worst;
		}
	c->frames++;
	return 0;
}

/* A scene of one flat colour (background only, unlit): every sample of the reference is the fill colour,
 * so the N-sample average is the fill colour exactly (the weights sum to one), whatever N is; and no
 * method can differ from it. */
static void test_flat_scene_reference_is_the_fill(void **state)
{
	(void)state;
	const int sizes[] = {2, 6, 16, 64};
	for (int k = 0; k < 4; k++) {
		struct aa_scene *scene;
		struct aa_error err = {0};
		float fg[3] = {0.25f, 0.5f, 0.125f}, bg[3] = {0.25f, 0.5f, 0.125f};
		struct aa_polygon2d poly[16];
		int n = aa_pattern2d_make(AA_PATTERN2D_HALF_PLANE, 30.0, 0, 0, 24, 16, poly);
		assert_int_equal(aa_scene_from_polygons(poly, n, 24, 16, fg, bg, &scene, &err), 0);
		const char *methods[] = {"none", "ssaa:4", "fxaa", "msaa:4"};
		struct aa_job_spec spec;
		fixture_spec(&spec, "flat", methods, 4, 24, 16, 2, sizes[k]);
		struct flat_capture c = {0};
		struct aa_job_result *r = fixture_run(&spec, scene, capture_flat, &c);
		printf("  flat fill, %d samples: reference differs from the fill by at most %g\n", sizes[k], c.worst);
		assert_int_equal(c.frames, 2);
		/* exact: a sum of N equal floats divided by N; float rounding of the sum is the only error */
		assert_true(c.worst <= 1e-6f);
		assert_true(r->reference.frames[0].convergence_identical);
		for (int m = 0; m < 4; m++)
			for (int f = 0; f < 2; f++)
				if (!r->methods[m].frames[f].metrics.identical)
					fail_msg("%s differs from a flat reference (PSNR %.2f)", methods[m],
						 r->methods[m].frames[f].metrics.psnr);
		fixture_free(r);
		aa_scene_free(scene);
	}
}

struct reference_frames {
	int count;
	uint64_t hash[2];
};

static int hash_reference(const struct aa_event *ev, void *user)
{
	struct reference_frames *c = user;
	if (ev->type != AA_EVENT_REFERENCE_FRAME || ev->frame_ordinal >= 2)
		return 0;
	uint64_t h = 14695981039346656037ull;
	for (size_t i = 0; i < (size_t)ev->image->width * ev->image->height * 4; i++)
		h = (h ^ ev->image->pixels[i]) * 1099511628211ull;
	c->hash[ev->frame_ordinal] = h;
	c->count++;
	return 0;
}

/* A held camera ("static") over a scene where nothing moves renders the reference once and reuses it; over
 * a scene where objects move, every frame's reference is rendered anew and shows them moved. */
static void test_reference_reuse(void **state)
{
	(void)state;
	const struct { const char *scene; bool moves; } cases[] = {{"thin-wires", false}, {"moving-sphere", true},
								   {"spinning-wheel", true}};
	for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
		const char *methods[] = {"none"};
		struct aa_job_spec spec;
		fixture_spec(&spec, cases[k].scene, methods, 1, 48, 27, 2, 4);
		snprintf(spec.path, sizeof spec.path, "static");
		struct reference_frames c = {0};
		struct aa_job_result *r = fixture_run(&spec, NULL, hash_reference, &c);
		assert_int_equal(c.count, 2);
		if (r->reference.frames[1].reused == cases[k].moves || (c.hash[0] != c.hash[1]) != cases[k].moves)
			fail_msg("%s, held camera: frame 1's reference %s and %s frame 0's", cases[k].scene,
				 r->reference.frames[1].reused ? "reused" : "rendered", c.hash[0] == c.hash[1] ? "equals" : "differs from");
		fixture_free(r);
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_flat_scene_reference_is_the_fill),
		cmocka_unit_test(test_reference_reuse),
		cmocka_unit_test(test_every_scene_every_method),
	};
	return fixture_status(cmocka_run_group_tests(tests, fixture_setup, fixture_teardown));
}
