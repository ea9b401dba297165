/* Stability of seed 000's temporal methods, asaa and t2msaa: (a) NaN/Inf injected into
 * one frame's shading never reaches history or output; (b) 2,000 frames of a still camera stay within
 * 0.5 dB of frame 100 (no drift, no stall); (c) a camera cut resets history: the frame after the cut
 * equals a fresh run started there; (d) velocities pointing off-screen are rejected, not clamped: pixels
 * entering the view during a fast pan are no worse than `none` there; (e) a surface 150,000 units away
 * still accumulates under motion (depth clamped at 65000 in half-float history would stop it). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#include <cmocka.h>

#include <jansson.h>

#include "run/engine.h"
#include "fixture.h"
#include "methods/methods.h"
#include "run/job_spec.h"

static const char *const methods[] = {"asaa", "t2msaa"};
#define METHODS 2
#define MAX_KEEP 8

/* What a run keeps: linear images of chosen frames (by ordinal) per method slot, and the references. */
struct capture {
	int keep_from, keep_count;
	int width, height;
	float *image[AA_MAX_METHODS][MAX_KEEP];
	float *reference[MAX_KEEP];
};

static float *copy_linear(const struct aa_image_rgbaf *img)
{
	size_t n = (size_t)img->width * img->height * 4;
	float *p = malloc(n * sizeof *p);
	assert_non_null(p);
	memcpy(p, img->pixels, n * sizeof *p);
	return p;
}

static int on_event(const struct aa_event *ev, void *user)
{
	struct capture *c = user;
	if (!c)
		return 0;
	int k = ev->frame_ordinal - c->keep_from;
	if (k < 0 || k >= c->keep_count)
		return 0;
	if (ev->type == AA_EVENT_METHOD_FRAME)
		c->image[ev->method_index][k] = copy_linear(ev->linear);
	else if (ev->type == AA_EVENT_REFERENCE_FRAME)
		c->reference[k] = copy_linear(ev->linear);
	return 0;
}

static void capture_free(struct capture *c)
{
	for (int k = 0; k < MAX_KEEP; k++) {
		free(c->reference[k]);
		for (int m = 0; m < AA_MAX_METHODS; m++)
			free(c->image[m][k]);
	}
}

static void spec_init(struct aa_job_spec *spec, const char *scene, const char *path, int w, int h, int frames,
		      int reference_samples, const char *const *names, int count)
{
	struct aa_error err = {0};
	aa_job_spec_defaults(spec);
	snprintf(spec->scene, sizeof spec->scene, "%s", scene);
	snprintf(spec->path, sizeof spec->path, "%s", path);
	spec->width = w;
	spec->height = h;
	spec->frames = frames;
	spec->reference_samples = reference_samples;
	spec->method_count = count;
	for (int i = 0; i < count; i++) {
		struct aa_method_spec *m = &spec->methods[i];
		if (aa_method_parse(names[i], "methods", &m->method, &m->params, &err))
			fail_msg("%s: %s", names[i], err.message);
		aa_method_label(m->method, &m->params, m->label, sizeof m->label);
	}
}

static struct aa_job_result *run(const struct aa_job_spec *spec, struct capture *c)
{
	return fixture_run(spec, NULL, on_event, c);
}

static double now_s(void)
{
	struct timespec t;
	clock_gettime(CLOCK_MONOTONIC, &t);
	return (double)t.tv_sec + t.tv_nsec / 1e9;
}

/* (a) frame 3's shading emits NaN and +Inf in a sparse pattern; the objects move, so history is used */
static void test_nonfinite_injection(void **state)
{
	(void)state;
	struct aa_job_spec spec;
	spec_init(&spec, "moving-sphere", "default", 64, 36, 8, 8, methods, METHODS);
	struct aa_job_result *clean = run(&spec, NULL);
	spec.inject_nonfinite_frame = 3;
	struct aa_job_result *hit = run(&spec, NULL);
	for (int m = 0; m < METHODS; m++) {
		for (int f = 0; f < spec.frames; f++)
			if (hit->methods[m].frames[f].nonfinite != 0)
				fail_msg("%s frame %d: %ld non-finite values in the output", methods[m], f,
					 hit->methods[m].frames[f].nonfinite);
		for (int f = 5; f < 8; f++) {
			double a = clean->methods[m].frames[f].metrics.psnr, b = hit->methods[m].frames[f].metrics.psnr;
			printf("  %-7s frame %d: PSNR %.2f dB clean, %.2f dB after the injection\n", methods[m], f, a, b);
			assert_true(fabs(a - b) < 0.5);
		}
	}
	fixture_free(clean);
	fixture_free(hit);
}

/* (b) a still camera over thin wires, 2,000 frames at 48x27: the reference is rendered once */
static void test_still_camera_long_run(void **state)
{
	(void)state;
	struct aa_job_spec spec;
	spec_init(&spec, "thin-wires", "static", 48, 27, 2000, 16, methods, METHODS);
	double t0 = now_s();
	struct aa_job_result *r = run(&spec, NULL);
	printf("  2,000 still frames of asaa + t2msaa in %.1f s\n", now_s() - t0);
	for (int m = 0; m < METHODS; m++) {
		const struct aa_frame_result *fr = r->methods[m].frames;
		double at100 = fr[100].metrics.psnr, lo = at100, hi = at100;
		for (int f = 100; f < spec.frames; f++) {
			assert_int_equal(fr[f].nonfinite, 0);
			lo = fmin(lo, fr[f].metrics.psnr);
			hi = fmax(hi, fr[f].metrics.psnr);
		}
		printf("  %-7s PSNR frame 0 %.2f, frame 100 %.2f, frames 100..1999 within [%.2f, %.2f], last %.2f\n",
		       methods[m], fr[0].metrics.psnr, at100, lo, hi, fr[spec.frames - 1].metrics.psnr);
		assert_true(isfinite(at100));
		assert_true(hi - at100 <= 0.5 && at100 - lo <= 0.5);
		assert_true(at100 > fr[0].metrics.psnr); /* accumulation helped and did not stall at frame 0 */
	}
	fixture_free(r);
}

static double max_abs_diff(const float *a, const float *b, int n)
{
	double d = 0;
	for (int i = 0; i < n; i++)
		d = fmax(d, fabs((double)a[i] - b[i]));
	return d;
}

/* (c) thin-wires' `fly` path cuts at 3 s (frame 90): frames 90 and 91 of a run from frame 84 must equal
 * a fresh run that starts at frame 90 */
static void test_cut_resets_history(void **state)
{
	(void)state;
	struct aa_job_spec spec;
	spec_init(&spec, "thin-wires", "fly", 64, 36, 8, 4, methods, METHODS);
	spec.first_frame = 84;
	struct capture through = {.keep_from = 6, .keep_count = 2};
	fixture_free(run(&spec, &through));
	spec.first_frame = 90;
	spec.frames = 2;
	struct capture fresh = {.keep_from = 0, .keep_count = 2};
	fixture_free(run(&spec, &fresh));
	for (int m = 0; m < METHODS; m++)
		for (int k = 0; k < 2; k++) {
			assert_non_null(through.image[m][k]);
			assert_non_null(fresh.image[m][k]);
			double d = max_abs_diff(through.image[m][k], fresh.image[m][k], 64 * 36 * 4);
			printf("  %-7s frame %d after the cut vs a fresh run: max |diff| %.3g\n", methods[m], 90 + k, d);
			assert_true(d < 1e-4);
		}
	capture_free(&through);
	capture_free(&fresh);
}

/* A copy of thin-wires whose camera whips round 90 degrees in half a second (3 degrees, several pixels,
 * per frame): a strip of pixels enters the view every frame, with velocities pointing off-screen. */
static void write_whip_scene(const char *path)
{
	char src[1024];
	struct aa_error err = {0};
	if (aa_scene_resolve("thin-wires", src, sizeof src, &err))
		fail_msg("%s", err.message);
	json_error_t je;
	json_t *scene = json_load_file(src, 0, &je);
	if (!scene)
		fail_msg("cannot read %s: %s", src, je.text);
	json_t *paths = json_pack("[{s:s, s:s, s:f, s:f}]", "name", "whip", "type", "pan", "degrees", -90.0,
				  "duration", 1.0);
	json_object_set_new(scene, "paths", paths);
	assert_int_equal(json_dump_file(scene, path, JSON_INDENT(1)), 0);
	json_decref(scene);
}

static double strip_mse(const float *img, const float *ref, int w, int h, int x0, int x1)
{
	double sum = 0;
	for (int y = 0; y < h; y++)
		for (int x = x0; x < x1; x++)
			for (int c = 0; c < 3; c++) {
				double d = img[(y * w + x) * 4 + c] - ref[(y * w + x) * 4 + c];
				sum += d * d;
			}
	return sum / ((double)h * (x1 - x0) * 3);
}

/* (d) on the edges of a whip pan, methods that fall back to the current frame err about as much as
 * `none`; a clamped history lookup would smear the old edge column across the new strip. */
static void test_offscreen_velocity_rejected(void **state)
{
	(void)state;
	char path[] = "/tmp/aalab-whip-XXXXXX.json";
	int fd = mkstemps(path, 5);
	assert_true(fd >= 0);
	close(fd);
	write_whip_scene(path);
	const char *names[] = {"none", "asaa", "t2msaa"};
	struct aa_job_spec spec;
	const int w = 96, h = 54;
	spec_init(&spec, path, "whip", w, h, 8, 8, names, 3);
	struct capture c = {.keep_from = 2, .keep_count = 6};
	fixture_free(run(&spec, &c));
	double err[3] = {0};
	for (int m = 0; m < 3; m++)
		for (int k = 0; k < c.keep_count; k++) /* both edges, 8 px: the entering strip is on one of them */
			err[m] += strip_mse(c.image[m][k], c.reference[k], w, h, 0, 8) +
				  strip_mse(c.image[m][k], c.reference[k], w, h, w - 8, w);
	printf("  edge strips during a whip pan, MSE (linear): none %.5f, asaa %.5f, t2msaa %.5f\n", err[0], err[1],
	       err[2]);
	for (int m = 1; m < 3; m++)
		assert_true(err[m] < 1.5 * err[0]);
	capture_free(&c);
	remove(path);
}

/* Mean squared error (linear) over rows [y0, y1). */
static double rows_mse(const float *img, const float *ref, int w, int y0, int y1)
{
	double sum = 0;
	for (int y = y0; y < y1; y++)
		for (int x = 0; x < w; x++)
			for (int c = 0; c < 3; c++) {
				double d = img[(y * w + x) * 4 + c] - ref[(y * w + x) * 4 + c];
				sum += d * d;
			}
	return sum / ((double)(y1 - y0) * w * 3);
}

/* (e) hdr-teleport's striped backdrop stands 150,000 units away, past half float's 65504. With its depth
 * clamped at 65000 in history, every reprojected sample of it failed the 8% disocclusion test while the
 * camera moved, and nothing there accumulated (error as none's). A slow pan over it: after 4 frames both
 * methods have averaged several samples, well under none's error on the backdrop's rows. */
static void test_far_surface_accumulates(void **state)
{
	(void)state;
	char file[1024];
	struct aa_error err = {0};
	struct aa_scene *scene;
	assert_int_equal(aa_scene_resolve("hdr-teleport", file, sizeof file, &err), 0);
	assert_int_equal(aa_scene_load(file, &scene, &err), 0);
	scene->paths[0].kind = AA_PATH_PAN;
	scene->paths[0].degrees = -8.0f; /* 0.07 degrees, ~0.3 px a frame at 160 px */
	scene->paths[0].duration = 4.0;
	scene->paths[0].key_count = 1;
	const char *names[] = {"none", "asaa", "t2msaa"};
	struct aa_job_spec spec;
	const int w = 160, h = 90;
	spec_init(&spec, "hdr-teleport", "default", w, h, 12, 32, names, 3);
	struct capture c = {.keep_from = 4, .keep_count = 8};
	fixture_free(fixture_run(&spec, scene, on_event, &c));
	double mse[3] = {0};
	for (int m = 0; m < 3; m++)
		for (int k = 0; k < c.keep_count; k++) /* the backdrop fills the top quarter of the view */
			mse[m] += rows_mse(c.image[m][k], c.reference[k], w, 0, h / 4) / c.keep_count;
	printf("  backdrop at 150,000 units during a slow pan, MSE (linear): none %.6f, asaa %.6f, t2msaa %.6f\n",
	       mse[0], mse[1], mse[2]);
	for (int m = 1; m < 3; m++)
		assert_true(mse[m] < 0.6 * mse[0]);
	capture_free(&c);
	aa_scene_free(scene);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_nonfinite_injection),
		cmocka_unit_test(test_cut_resets_history),
		cmocka_unit_test(test_offscreen_velocity_rejected),
		cmocka_unit_test(test_far_surface_accumulates),
		cmocka_unit_test(test_still_camera_long_run),
	};
	return fixture_status(cmocka_run_group_tests(tests, fixture_setup, fixture_teardown));
}
