/* Stability of taa and taa-sobel: NaN/Inf injected into one frame never reaches
 * history or output; a camera cut resets history; during a fast pan over a textured wall, history that
 * reprojects from off-screen is rejected rather than clamped into garbage and the rest is reprojected
 * the right way; a still camera: preset=accumulate converges (64 frames: no PSNR spread, no flicker), the
 * default production TAA beats none without reaching ssaa:16; after an HDR
 * camera teleport without a cut the bright ball stays close to the reference in every frame. */
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
#include "methods/methods.h"

static const char *const temporal[] = {"taa", "taa-sobel"};

static void make_spec(struct aa_job_spec *spec, const char *scene, const char *path, const char *const *methods,
		      int n, int w, int h, int first, int frames, int samples)
{
	fixture_spec(spec, scene, methods, n, w, h, frames, samples);
	snprintf(spec->path, sizeof spec->path, "%s", path);
	spec->first_frame = first;
}

/* Keeps a copy of every method's 8-bit output per frame, and the reference's after them. */
struct frames {
	int methods, count, w, h; /* methods: slots per frame, the method count + 1 */
	uint8_t *pixels; /* [frame][method or reference][w*h*4] */
};

static int keep_frames(const struct aa_event *ev, void *user)
{
	struct frames *f = user;
	size_t size = (size_t)f->w * f->h * 4;
	if (ev->type == AA_EVENT_METHOD_FRAME)
		memcpy(f->pixels + ((size_t)ev->frame_ordinal * f->methods + ev->method_index) * size,
		       ev->image->pixels, size);
	else if (ev->type == AA_EVENT_REFERENCE_FRAME)
		memcpy(f->pixels + ((size_t)ev->frame_ordinal * f->methods + f->methods - 1) * size,
		       ev->image->pixels, size);
	return 0;
}

static struct aa_job_result *run(const struct aa_job_spec *spec, const struct aa_scene *scene, struct frames *f)
{
	if (f) {
		f->methods = spec->method_count + 1;
		f->count = spec->frames;
		f->w = spec->width;
		f->h = spec->height;
		f->pixels = calloc((size_t)f->count * f->methods, (size_t)f->w * f->h * 4);
	}
	return fixture_run(spec, scene, f ? keep_frames : NULL, f);
}

/* (a) one frame of NaN/+Inf shading: no NaN/Inf in any output, and two frames later the image is back
 * to within 1 dB of a clean run. */
static void test_nonfinite_never_reaches_history(void **state)
{
	(void)state;
	struct aa_job_spec spec;
	make_spec(&spec, "thin-wires", "static", temporal, 2, 96, 54, 0, 8, 8);
	struct aa_job_result *clean = run(&spec, NULL, NULL);
	spec.inject_nonfinite_frame = 3;
	struct aa_job_result *poisoned = run(&spec, NULL, NULL);
	for (int m = 0; m < 2; m++)
		for (int f = 0; f < 8; f++) {
			const struct aa_frame_result *fr = &poisoned->methods[m].frames[f];
			if (fr->nonfinite)
				fail_msg("%s frame %d: %ld NaN/Inf values in the output", temporal[m], f, fr->nonfinite);
			if (f >= 5) {
				double a = clean->methods[m].frames[f].metrics.psnr, b = fr->metrics.psnr;
				printf("  %s frame %d: clean %.2f dB, after injection %.2f dB\n", temporal[m], f, a, b);
				assert_true(fabs(a - b) < 1.0);
			}
		}
	fixture_free(clean);
	fixture_free(poisoned);
}

/* (c) the first frame after a camera cut equals a fresh start at that frame: no trace of the old view. */
static void test_cut_resets_history(void **state)
{
	(void)state;
	/* thin-wires' "fly" path cuts at t = 3 s, frame 90 at 30 fps */
	struct aa_job_spec spec;
	struct frames across = {0}, fresh = {0};
	make_spec(&spec, "thin-wires", "fly", temporal, 2, 96, 54, 86, 6, 2);
	fixture_free(run(&spec, NULL, &across));
	make_spec(&spec, "thin-wires", "fly", temporal, 2, 96, 54, 90, 1, 2);
	fixture_free(run(&spec, NULL, &fresh));
	size_t size = 96 * 54 * 4;
	for (int m = 0; m < 2; m++) {
		const uint8_t *a = across.pixels + ((size_t)4 * across.methods + m) * size, *b = fresh.pixels + (size_t)m * size;
		int max = 0;
		for (size_t i = 0; i < size; i++)
			max = abs(a[i] - b[i]) > max ? abs(a[i] - b[i]) : max;
		printf("  %s: frame after the cut vs a fresh start there: max difference %d\n", temporal[m], max);
		assert_true(max <= 1);
	}
	free(across.pixels);
	free(fresh.pixels);
}

/* Mean over frames and pixels of |a - b| in 8-bit levels, R, G and B, in columns [x0, x1) of frames
 * [t0, t1) of two methods' kept frames. */
static double mean_difference(const struct frames *f, int ma, int mb, int t0, int t1, int x0, int x1)
{
	size_t size = (size_t)f->w * f->h * 4;
	double sum = 0.0;
	for (int t = t0; t < t1; t++) {
		const uint8_t *a = f->pixels + ((size_t)t * f->methods + ma) * size;
		const uint8_t *b = f->pixels + ((size_t)t * f->methods + mb) * size;
		for (int y = 0; y < f->h; y++)
			for (int x = x0; x < x1; x++)
				for (int c = 0; c < 3; c++) {
					size_t i = ((size_t)y * f->w + (size_t)x) * 4 + (size_t)c;
					sum += abs((int)a[i] - (int)b[i]);
				}
	}
	return sum / ((double)(t1 - t0) * f->h * (x1 - x0) * 3);
}

/* (d) A fast pan to the right (2 degrees a frame, ~5 px at 160 px) across moving-sphere's brick wall.
 * Pixels entering at the right edge have their history off-screen: rejected, the entering strip shows
 * this frame's content and is about as far from the reference as none is there; clamped to the border,
 * the border's bricks would be smeared across it. The rest of the frame reprojects: with the converging
 * resolve every frame after the first scores better than none (history fetched from the wrong place,
 * e.g. along a flipped velocity, ghosts the whole wall). */
static void test_fast_pan_over_texture(void **state)
{
	(void)state;
	char file[1024];
	struct aa_error err = {0};
	struct aa_scene *scene;
	assert_int_equal(aa_scene_resolve("moving-sphere", file, sizeof file, &err), 0);
	assert_int_equal(aa_scene_load(file, &scene, &err), 0);
	scene->paths[0].kind = AA_PATH_PAN;
	scene->paths[0].degrees = -240.0f; /* 2 degrees a frame at 30 fps, turning right */
	scene->paths[0].duration = 4.0;
	const char *methods[] = {"none", "taa", "taa-sobel", "taa:preset=seed001"};
	struct aa_job_spec spec;
	struct frames f = {0};
	make_spec(&spec, "moving-sphere-fast-pan", "default", methods, 4, 160, 90, 0, 8, 32);
	struct aa_job_result *r = run(&spec, scene, &f);
	int reference = f.methods - 1;
	double none = mean_difference(&f, 0, reference, 1, 8, 152, 160);
	for (int m = 1; m < 4; m++) {
		double strip = mean_difference(&f, m, reference, 1, 8, 152, 160), worst = 1e9;
		for (int t = 1; t < 8; t++) {
			double d = r->methods[m].frames[t].metrics.psnr - r->methods[0].frames[t].metrics.psnr;
			worst = d < worst ? d : worst;
		}
		printf("  %s: entering strip %.2f levels from the reference (none %.2f); worst frame after the "
		       "first %+.2f dB against none\n", methods[m], strip, none, worst);
		assert_true(strip < none + 1.5);
		/* seed 001's resolve, kept as it was, scores 0.1 dB under none in one frame */
		assert_true(worst > (m == 3 ? -0.5 : 0.3));
	}
	for (int m = 0; m < 4; m++)
		for (int t = 0; t < 8; t++)
			assert_int_equal(r->methods[m].frames[t].nonfinite, 0);
	fixture_free(r);
	free(f.pixels);
	aa_scene_free(scene);
}

/* Still thin wires, 64 frames, preset=accumulate (linear: the best case an accumulating TAA reaches):
 * after a warm-up of two jitter cycles the image has converged, so its PSNR does not move and it does not
 * flicker, well ahead of none. Seed 001's resolve swings by 0.6 dB with the jitter and flickers at ~3
 * here; the bounds leave it no chance. */
static void test_still_camera_accumulates(void **state)
{
	(void)state;
	const char *methods[] = {"none", "taa:preset=accumulate,tonemapped_resolve=false",
				 "taa-sobel:preset=accumulate,tonemapped_resolve=false"};
	struct aa_job_spec spec;
	/* 64 reference samples: the reference's error well under the margins below */
	make_spec(&spec, "thin-wires", "static", methods, 3, 160, 90, 0, 64, 64);
	struct aa_job_result *r = run(&spec, NULL, NULL);
	double none = r->methods[0].frames[63].metrics.psnr;
	for (int m = 1; m < 3; m++) {
		const struct aa_frame_result *fr = r->methods[m].frames;
		double lo = 1e9, hi = -1e9, flicker = 0.0;
		for (int t = 32; t < 64; t++) {
			lo = fr[t].metrics.psnr < lo ? fr[t].metrics.psnr : lo;
			hi = fr[t].metrics.psnr > hi ? fr[t].metrics.psnr : hi;
			flicker += fr[t].flicker / 32.0;
		}
		printf("  %s, frames 32-63: PSNR %.2f to %.2f dB (none %.2f), flicker %.3f\n", methods[m], lo, hi, none,
		       flicker);
		assert_true(hi - lo < 0.1);
		assert_true(flicker < 0.05);
		assert_true(lo > none + 10.0);
	}
	fixture_free(r);
}

/* Still thin wires, 64 frames, the default (preset=production, a TAA as engines ship it): frames 32-63
 * beat none by a margin and flicker less than seed 001's resolve, but the clip every frame keeps it from
 * sitting at the reference: it stays under ssaa:16 and still moves with the jitter. (A TAA whose jitter
 * points were the reference's own, or that stopped clipping still pixels, would sit far above ssaa:16.) */
static void test_still_camera_production(void **state)
{
	(void)state;
	const char *methods[] = {"none", "taa", "taa:preset=seed001", "ssaa:16"};
	struct aa_job_spec spec;
	make_spec(&spec, "thin-wires", "static", methods, 4, 160, 90, 0, 64, 64);
	struct aa_job_result *r = run(&spec, NULL, NULL);
	double mean[4] = {0}, flicker[4] = {0}, lo = 1e9, hi = -1e9;
	for (int m = 0; m < 4; m++)
		for (int t = 32; t < 64; t++) {
			const struct aa_frame_result *fr = &r->methods[m].frames[t];
			mean[m] += fr->metrics.psnr / 32.0;
			flicker[m] += fr->flicker / 32.0;
			if (m == 1) {
				lo = fr->metrics.psnr < lo ? fr->metrics.psnr : lo;
				hi = fr->metrics.psnr > hi ? fr->metrics.psnr : hi;
			}
		}
	printf("  frames 32-63: none %.2f dB, taa %.2f (%.2f to %.2f, flicker %.3f), seed001 %.2f (flicker %.3f), "
	       "ssaa:16 %.2f\n", mean[0], mean[1], lo, hi, flicker[1], mean[2], flicker[2], mean[3]);
	assert_true(mean[1] > mean[0] + 1.0);
	assert_true(flicker[1] < flicker[2]);
	assert_true(mean[1] < mean[3]);
	assert_true(hi - lo > 0.05);
	fixture_free(r);
}

/* The first frame is reconstructed at the pixel centre from the jittered samples, so it is no worse than
 * none (frame 0 of seed 001's resolve is the jittered image, shifted by up to half a pixel:
 * hard-edges at 320x180 0.6 dB under none). */
static void test_first_frame(void **state)
{
	(void)state;
	const char *methods[] = {"none", "taa", "taa-sobel"};
	struct aa_job_spec spec;
	make_spec(&spec, "hard-edges", "static", methods, 3, 320, 180, 0, 1, 32);
	struct aa_job_result *r = run(&spec, NULL, NULL);
	double none = r->methods[0].frames[0].metrics.psnr;
	for (int m = 1; m < 3; m++) {
		double p = r->methods[m].frames[0].metrics.psnr;
		printf("  hard-edges 320x180, first frame: none %.2f dB, %s %.2f dB\n", none, methods[m], p);
		assert_true(p > none - 0.2);
	}
	fixture_free(r);
}

/* The ball's pixels: where the reference frame is the ball's saturated yellow. */
static bool is_ball(const uint8_t *px)
{
	return px[0] > 180 && px[1] > 140 && px[2] < 90;
}

struct teleport_frames {
	int w, h, count;
	uint8_t *reference, *taa; /* [frame][w*h*4] */
};

static int keep_teleport(const struct aa_event *ev, void *user)
{
	struct teleport_frames *f = user;
	size_t size = (size_t)f->w * f->h * 4;
	if (ev->type == AA_EVENT_REFERENCE_FRAME)
		memcpy(f->reference + (size_t)ev->frame_ordinal * size, ev->image->pixels, size);
	else if (ev->type == AA_EVENT_METHOD_FRAME && ev->method_index == 1)
		memcpy(f->taa + (size_t)ev->frame_ordinal * size, ev->image->pixels, size);
	return 0;
}

/* (e) hdr-teleport: the camera jumps at frame 30 without a cut, so velocities after it come from the old
 * view, where a screen hid the ball; the ball, hundreds of times brighter than the floor and ~7 px
 * across at 320x180, crosses the new view at ~15 px a frame. In every frame after the teleport its
 * pixels stay within 40 levels of the reference on average (drawn as floor they would be ~100 off) and
 * within 18 on average over the 13 frames (measured 15.3; a clamp instead of the clip toward the box
 * centre keeps more stale history: 20.5); the frame as a whole scores no lower than none by more than
 * 1 dB (seed 001's resolve falls 1.45 dB below none on the teleport frame); in every frame at least half
 * of the reference's ball pixels are ball-coloured in taa's (with UE4's motion weight of 0.2 at 40 px,
 * or Karis' weights in the 3x3 filter at any speed, the last frames kept under half). */
static void test_hdr_teleport(void **state)
{
	(void)state;
	for (int k = 0; k < 2; k++) {
		const char *methods[] = {"none", k ? "taa-sobel" : "taa"};
		const int first = 28, frames = 16, w = 320, h = 180;
		struct aa_job_spec spec;
		make_spec(&spec, "hdr-teleport", "default", methods, 2, w, h, first, frames, 32);
		size_t size = (size_t)w * h * 4;
		struct teleport_frames f = {w, h, frames, calloc(frames, size), calloc(frames, size)};
		struct aa_job_result *r = fixture_run(&spec, NULL, keep_teleport, &f);
		double worst_ball = 0.0, mean_ball = 0.0, worst_db = 1e9, worst_kept = 1.0;
		int after = 0;
		for (int t = 31 - first; t < frames; t++, after++) {
			double sum = 0.0;
			int n = 0, kept = 0;
			for (size_t i = 0; i < size; i += 4)
				if (is_ball(f.reference + (size_t)t * size + i)) {
					for (int c = 0; c < 3; c++)
						sum += abs((int)f.taa[(size_t)t * size + i + (size_t)c] -
							   (int)f.reference[(size_t)t * size + i + (size_t)c]);
					n++;
					kept += is_ball(f.taa + (size_t)t * size + i);
				}
			if (n < 16) /* the ball is in view in every frame after the teleport */
				fail_msg("frame %d: %d ball pixels in the reference", first + t, n);
			double ball = sum / (3.0 * n);
			double db = r->methods[1].frames[t].metrics.psnr - r->methods[0].frames[t].metrics.psnr;
			printf("    %s frame %d: ball pixels %.1f levels off the reference, %d of %d kept, frame %+.2f dB "
			       "against none\n", methods[1], first + t, ball, kept, n, db);
			worst_kept = (double)kept / n < worst_kept ? (double)kept / n : worst_kept;
			worst_ball = ball > worst_ball ? ball : worst_ball;
			mean_ball += ball;
			worst_db = db < worst_db ? db : worst_db;
		}
		mean_ball /= after;
		printf("  %s after the teleport: ball pixels %.1f levels off on average, at most %.1f; at least %.0f%% "
		       "of them kept; frames at worst %+.2f dB against none\n", methods[1], mean_ball, worst_ball,
		       100.0 * worst_kept, worst_db);
		assert_true(worst_ball < 40.0);
		assert_true(worst_kept >= 0.5); /* the ball keeps half its pixels in every frame */
		assert_true(mean_ball < 18.0);
		assert_true(worst_db > -1.0);
		fixture_free(r);
		free(f.reference);
		free(f.taa);
	}
}

/* fast-ball (docs/hard-cases.md): a small bright ball swinging at up to ~20 px/frame at 160x90, the
 * camera jumping at frame 31 without a cut (path jump) or with one and then swinging fast (cut-swing):
 * in every frame, taa and taa-sobel keep at least half of the reference's ball pixels. */
static void test_fast_ball(void **state)
{
	(void)state;
	const char *methods[] = {"none", "taa", "taa-sobel"};
	const char *paths[] = {"jump", "cut-swing"};
	const int first = 28, frames = 16, w = 160, h = 90;
	for (int k = 0; k < 2; k++) {
		struct aa_job_spec spec;
		struct frames f = {0};
		make_spec(&spec, "fast-ball", paths[k], methods, 3, w, h, first, frames, 32);
		fixture_free(run(&spec, NULL, &f));
		size_t size = (size_t)w * h * 4;
		for (int m = 1; m < 3; m++) {
			double worst = 1.0;
			int worst_frame = -1, judged = 0;
			for (int t = 0; t < frames; t++) {
				const uint8_t *ref = f.pixels + ((size_t)t * f.methods + f.methods - 1) * size;
				const uint8_t *out = f.pixels + ((size_t)t * f.methods + m) * size;
				int n = 0, kept = 0;
				for (size_t i = 0; i < size; i += 4)
					if (is_ball(ref + i)) {
						n++;
						kept += is_ball(out + i);
					}
				if (n < 16) { /* the swing turns the camera away from the ball */
					if (k == 0)
						fail_msg("%s frame %d: %d ball pixels in the reference", paths[k], first + t, n);
					continue;
				}
				judged++;
				if ((double)kept / n < worst) {
					worst = (double)kept / n;
					worst_frame = first + t;
				}
			}
			printf("  fast-ball %s, %s: at least %.0f%% of the ball's pixels kept (frame %d) over the %d frames "
			       "it is in view\n", paths[k], methods[m], 100.0 * worst, worst_frame, judged);
			assert_true(judged >= 8);
			assert_true(worst >= 0.5);
		}
		free(f.pixels);
	}
}

/* The parameters: seed 001's defaults (16 Halton points, INSIDE's feedback range 0.88-0.97), HDRP's
 * current-frame weight 0.125 and Karis' weights on; the preset that ran named in path_taken; a parameter
 * that the chosen preset ignores refused, naming the field. Raising the default feedback_max to 0.99
 * barely shows in images (it bounds the history weight only where current and history already agree:
 * moving-sphere 0.02 dB), so it is checked here. */
static void test_taa_parameters(void **state)
{
	(void)state;
	const char *names[] = {"taa", "taa-sobel"};
	for (int k = 0; k < 2; k++) {
		const struct aa_method *m;
		struct aa_method_params p;
		struct aa_error err = {0};
		assert_int_equal(aa_method_parse(names[k], "methods[0]", &m, &p, &err), 0);
		double want[] = {16, 0.88, 0.97, 0.125, 1, 0};
		const char *keys[] = {"jitter_length", "feedback_min", "feedback_max", "current_weight",
				      "tonemapped_resolve", "preset"};
		for (int i = 0; i < 6; i++) {
			int at = aa_method_param_index(m, keys[i]);
			assert_true(at >= 0);
			if (p.v[at] != want[i])
				fail_msg("%s: default %s is %g, expected %g", names[k], keys[i], p.v[at], want[i]);
		}
		assert_string_equal(m->params[aa_method_param_index(m, "preset")].choices[0], "production");
		/* each preset names itself in path_taken */
		char a[64], b[64], c[64];
		snprintf(a, sizeof a, "%s", names[k]);
		snprintf(b, sizeof b, "%s:preset=accumulate", names[k]);
		snprintf(c, sizeof c, "%s:preset=seed001", names[k]);
		const char *presets[] = {a, b, c};
		const char *says[] = {"preset production: ", "preset accumulate: ", "preset seed001: "};
		struct aa_job_spec spec;
		make_spec(&spec, "thin-wires", "static", presets, 3, 32, 18, 0, 1, 2);
		struct aa_job_result *r = run(&spec, NULL, NULL);
		for (int i = 0; i < 3; i++) {
			printf("  %s: %s\n", presets[i], r->methods[i].path_taken);
			assert_true(strncmp(r->methods[i].path_taken, says[i], strlen(says[i])) == 0);
		}
		fixture_free(r);
		/* parameters the preset ignores */
		const char *refused[][2] = {{"%s:preset=seed001,clip=aabb", "params.clip"},
					    {"%s:preset=seed001,current_weight=0.1", "params.current_weight"},
					    {"%s:preset=accumulate,current_weight=0.1", "params.current_weight"},
					    {"%s:max_samples=16", "params.max_samples"},
					    {"%s:feedback_min=0.5", "params.feedback_min"}};
		for (int i = 0; i < 5; i++) {
			char text[96];
			snprintf(text, sizeof text, refused[i][0], names[k]);
			const char *method[] = {text};
			make_spec(&spec, "thin-wires", "static", method, 1, 32, 18, 0, 1, 2);
			r = NULL;
			memset(&err, 0, sizeof err);
			int rc = aa_job_run_scene(fixture_engine, &spec, NULL, NULL, NULL, &r, &err);
			printf("  %s: %s: %s\n", text, err.path, err.message);
			assert_int_not_equal(rc, 0);
			assert_int_equal(err.code, AA_ERR_INVALID);
			assert_string_equal(err.path, refused[i][1]);
			fixture_free(r);
		}
	}
}

/* The resolves (compute, and seed001's full-screen one) write the displayed image themselves: no copy
 * pass after them unless sharpen is on, and what they display without sharpening is the picture (every
 * frame within 1 dB of none's or better), not a stale or empty image. */
static void test_display_in_resolve(void **state)
{
	(void)state;
	const char *methods[] = {"none", "taa", "taa-sobel", "taa:preset=accumulate", "taa:sharpen=normalized",
				 "taa:preset=seed001", "taa-sobel:preset=seed001", "taa:preset=seed001,sharpen=original"};
	/* a taa-sharpen pass: sharpening only */
	const bool sharpened[] = {false, false, false, false, true, false, false, true};
	const int count = (int)(sizeof methods / sizeof methods[0]);
	struct aa_job_spec spec;
	make_spec(&spec, "thin-wires", "static", methods, count, 64, 36, 0, 3, 8);
	struct aa_job_result *r = run(&spec, NULL, NULL);
	for (int m = 1; m < count; m++)
		for (int t = 0; t < 3; t++) {
			const struct aa_frame_result *fr = &r->methods[m].frames[t];
			bool sharpen = false;
			for (int k = 0; k < fr->pass_count; k++)
				sharpen |= !strcmp(fr->passes[k].name, "taa-sharpen");
			if (sharpen != sharpened[m])
				fail_msg("%s frame %d: taa-sharpen %s", methods[m], t, sharpen ? "recorded" : "missing");
			const double none = r->methods[0].frames[t].metrics.psnr, mine = fr->metrics.psnr;
			if (!sharpened[m] && mine < none - 1.0) /* a sharpening kernel lowers PSNR (docs/methods.md) */
				fail_msg("%s frame %d: %.2f dB against none's %.2f", methods[m], t, mine, none);
		}
	fixture_free(r);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_nonfinite_never_reaches_history),
		cmocka_unit_test(test_cut_resets_history),
		cmocka_unit_test(test_fast_pan_over_texture),
		cmocka_unit_test(test_still_camera_accumulates),
		cmocka_unit_test(test_still_camera_production),
		cmocka_unit_test(test_first_frame),
		cmocka_unit_test(test_hdr_teleport),
		cmocka_unit_test(test_fast_ball),
		cmocka_unit_test(test_taa_parameters),
		cmocka_unit_test(test_display_in_resolve),
	};
	return fixture_status(cmocka_run_group_tests(tests, fixture_setup, fixture_teardown));
}
