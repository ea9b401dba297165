/* No method samples where the reference does. Every registered method's sample positions (standard MSAA
 * patterns, SSAA grids, every jitter sequence over many frames, RSAA's subsamples, the pixel centre of the
 * single-sample methods) at every allowed value of the parameters that move them, and the user methods'
 * jitter, are compared with all AA_MAX_REFERENCE_SAMPLES reference positions: none may lie within
 * COINCIDE pixels of one (modulo the pixel, as a sample in the next pixel at the same place is the same
 * point of the image's pattern). A method this test does not know fails it, so a new method must list
 * its positions here. The checker itself is checked on a pattern that does share positions. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "gpu/sample_positions.h"
#include "methods/jitter.h"
#include "methods/methods.h"
#include "methods/smaa.h"
#include "reference/reference.h"
#include "types/job.h"
#include "types/method.h"
#include "util/halton.h"

/* Well above float rounding (6e-8), far below any spacing that would make two samples independent. */
#define COINCIDE 1e-4
#define FRAMES 256 /* frames of each jitter sequence: every cycle of the temporal methods repeats within it */
#define MAX_POINTS 8192

struct points {
	int n;
	float p[MAX_POINTS][2]; /* in [0, 1)^2: where in the pixel the sample falls */
};

static void add(struct points *s, double x, double y)
{
	assert_true(s->n < MAX_POINTS);
	s->p[s->n][0] = (float)(x - floor(x));
	s->p[s->n][1] = (float)(y - floor(y));
	s->n++;
}

/* A method that draws the scene moved by jitter j samples the pixel at centre - j. */
static void add_jitter(struct points *s, const float j[2])
{
	add(s, 0.5 - j[0], 0.5 - j[1]);
}

static const struct aa_param_def *param(const struct aa_method *m, const char *name)
{
	int i = aa_method_param_index(m, name);
	if (i < 0)
		fail_msg("%s has no parameter %s: this test reads its positions from it", m->name, name);
	return &m->params[i];
}

static void add_standard(struct points *s, int n)
{
	const float (*pos)[2] = aa_standard_sample_positions(n);
	assert_non_null(pos);
	for (int i = 0; i < n; i++)
		add(s, pos[i][0], pos[i][1]);
}

static void add_halton_jitter(struct points *s, int length)
{
	for (int f = 0; f < FRAMES; f++) {
		float j[2];
		aa_jitter_halton(f, length, j);
		add_jitter(s, j);
	}
}

/* The positions of method m at every allowed value of its sample-moving parameters; false if this test
 * does not know m. */
static bool method_points(const struct aa_method *m, struct points *s)
{
	const char *name = m->name;
	if (!strcmp(name, "none") || !strcmp(name, "copy") || !strcmp(name, "floor") || !strcmp(name, "fxaa") ||
	    !strcmp(name, "fxaa-cs") || !strcmp(name, "gbaa") || !strcmp(name, "cmaa2")) {
		add(s, 0.5, 0.5); /* one sample at the pixel centre */
		return true;
	}
	if (!strcmp(name, "smaa")) {
		/* every mode's samples on both frames of its pair, taken either side of the centre (a sample
		 * offset and a scene jitter move the sampled point in opposite directions) */
		for (int mode = AA_SMAA_1X; mode <= AA_SMAA_4X; mode++)
			for (int f = 0; f < 2; f++) {
				int count;
				const struct aa_smaa_sample *smp = aa_smaa_frame_samples(mode, f, &count);
				for (int i = 0; i < count; i++) {
					add(s, 0.5 + smp[i].offset[0], 0.5 + smp[i].offset[1]);
					add(s, 0.5 - smp[i].offset[0], 0.5 - smp[i].offset[1]);
				}
			}
		return true;
	}
	if (!strcmp(name, "ssaa")) {
		for (const int *n = param(m, "samples")->allowed; *n; n++) {
			int k = (int)lround(sqrt(*n));
			for (int y = 0; y < k; y++)
				for (int x = 0; x < k; x++)
					add(s, (x + 0.5) / k, (y + 0.5) / k);
		}
		return true;
	}
	if (!strcmp(name, "msaa")) {
		for (const int *n = param(m, "samples")->allowed; *n; n++)
			add_standard(s, *n);
		return true;
	}
	if (!strcmp(name, "rsaa")) {
		add(s, 0.5, 0.5); /* the shaded centre pass */
		for (const int *n = param(m, "samples")->allowed; *n; n++)
			add_standard(s, *n);
		return true;
	}
	if (!strcmp(name, "taa") || !strcmp(name, "taa-sobel")) {
		for (const int *n = param(m, "jitter_length")->allowed; *n; n++)
			add_halton_jitter(s, *n);
		return true;
	}
	if (!strcmp(name, "t2msaa")) {
		const float (*pos)[2] = aa_standard_sample_positions(2);
		for (const char *const *c = param(m, "offset")->choices; *c; c++)
			for (int f = 0; f < 2; f++) {
				float j[2];
				aa_jitter_alternate(f, (float)atof(*c), j);
				for (int i = 0; i < 2; i++) /* mirrored in y, as t2msaa.c draws it */
					add(s, pos[i][0] + j[0], pos[i][1] - j[1]);
			}
		return true;
	}
	if (!strcmp(name, "asaa")) {
		const struct aa_param_def *sigma = param(m, "sigma");
		const double sigmas[] = {sigma->def, sigma->min, sigma->max};
		for (int k = 0; k < 3; k++)
			for (int f = 0; f < FRAMES; f++) {
				float phi[2], g[2];
				aa_jitter_quadrant(f & 3, phi);
				aa_jitter_gaussian(f, (float)sigmas[k], g);
				/* asaa.c draws the scene moved by -(phi + g) */
				add(s, 0.5 + phi[0] + g[0], 0.5 + phi[1] + g[1]);
			}
		return true;
	}
	return false;
}

/* How many of the first n reference positions lie within COINCIDE of one of s; the first is described in
 * where. */
static int coincidences(const struct points *s, const float (*ref)[2], int n, char *where, size_t size)
{
	int found = 0;
	for (int r = 0; r < n; r++) {
		double rx = 0.5 - ref[r][0], ry = 0.5 - ref[r][1];
		for (int i = 0; i < s->n; i++) {
			double dx = fabs(rx - s->p[i][0]), dy = fabs(ry - s->p[i][1]);
			dx = fmin(dx, 1.0 - dx);
			dy = fmin(dy, 1.0 - dy);
			if (dx * dx + dy * dy < COINCIDE * COINCIDE) {
				if (!found++)
					snprintf(where, size, "reference sample %d at (%.7f, %.7f), method sample (%.7f, %.7f)",
						 r, rx, ry, s->p[i][0], s->p[i][1]);
				break;
			}
		}
	}
	return found;
}

static void test_no_method_shares_reference_samples(void **state)
{
	(void)state;
	static float ref[AA_MAX_REFERENCE_SAMPLES][2];
	aa_reference_offsets(AA_MAX_REFERENCE_SAMPLES, ref);
	static struct points s;
	for (int i = 0; i < aa_method_count; i++) {
		s.n = 0;
		if (!method_points(aa_methods[i], &s))
			fail_msg("%s: its sample positions are not listed in this test; add them", aa_methods[i]->name);
		char where[160] = "";
		int n = coincidences(&s, ref, AA_MAX_REFERENCE_SAMPLES, where, sizeof where);
		if (n)
			fail_msg("%s shares %d of the reference's %d sample positions: %s", aa_methods[i]->name, n,
				 AA_MAX_REFERENCE_SAMPLES, where);
	}
	/* user methods: taa's Halton jitter of length 8 or 16 (user_method_file.c), or the pixel centre */
	s.n = 0;
	add(&s, 0.5, 0.5);
	add_halton_jitter(&s, 8);
	add_halton_jitter(&s, 16);
	char where[160] = "";
	int n = coincidences(&s, ref, AA_MAX_REFERENCE_SAMPLES, where, sizeof where);
	if (n)
		fail_msg("user methods share %d reference sample positions: %s", n, where);
}

/* The checker finds shared positions: Halton(2,3) points 1..64 (a pattern that shares the first 16 with
 * taa's jitter) against taa's positions. */
static void test_checker_finds_shared_positions(void **state)
{
	(void)state;
	float halton[64][2];
	for (int i = 0; i < 64; i++) {
		halton[i][0] = (float)(aa_halton((unsigned)i + 1, 2) - 0.5);
		halton[i][1] = (float)(aa_halton((unsigned)i + 1, 3) - 0.5);
	}
	static struct points s;
	s.n = 0;
	assert_true(method_points(aa_method_find("taa"), &s));
	char where[160];
	assert_int_equal(coincidences(&s, halton, 64, where, sizeof where), 16);
	/* a point a little more than COINCIDE away does not count, one a little less does */
	s.n = 0;
	add(&s, 0.25, 0.25);
	float near[2][2] = {{0.25f - 1.2e-4f, 0.25f}, {0.25f, 0.25f + 0.8e-4f}};
	assert_int_equal(coincidences(&s, near, 1, where, sizeof where), 0);
	assert_int_equal(coincidences(&s, near + 1, 1, where, sizeof where), 1);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_no_method_shares_reference_samples),
		cmocka_unit_test(test_checker_finds_shared_positions),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
