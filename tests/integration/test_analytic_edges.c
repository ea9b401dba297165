/* Every method against the exact box-filtered coverage of flat 2D patterns (zero reference error): a
 * half-plane at 0..90 degrees in steps of 5, and a bar 0.5 px wide. Prints each method's mean absolute
 * coverage error; every method must beat `none` on the half-planes, msaa:8 and smaa must beat fxaa on
 * near-horizontal edges, and methods that lose the thin bar are reported, not hidden. Temporal methods
 * (those that keep history) are scored on the last of TEMPORAL_FRAMES static frames, since their first
 * frame is a single jittered sample by design. */
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
#include "reference/exact_coverage.h"
#include "methods/methods.h"
#include "run/job_spec.h"

#define SIZE 64
#define ANGLES 19
#define TEMPORAL_FRAMES 8

static struct aa_job_spec spec;             /* every method: labels and indices of the results */
static struct aa_job_spec single, temporal; /* the single-frame and the history-keeping methods */
static int single_index[AA_MAX_METHODS], temporal_index[AA_MAX_METHODS]; /* into spec */
static double error_at[AA_MAX_METHODS][ANGLES]; /* mean abs coverage error per method and angle */

struct capture {
	const double *coverage;
	double *errors;      /* per method of spec */
	const int *index;    /* job method index -> spec index */
	int last_frame;      /* only this frame is scored */
};

static int on_event(const struct aa_event *ev, void *user)
{
	struct capture *c = user;
	if (ev->type != AA_EVENT_METHOD_FRAME || ev->frame_ordinal != c->last_frame)
		return 0;
	const struct aa_image_rgbaf *img = ev->linear;
	double sum = 0;
	for (int i = 0; i < SIZE * SIZE; i++)
		sum += fabs(img->pixels[i * 4] - c->coverage[i]);
	c->errors[c->index[ev->method_index]] = sum / (SIZE * SIZE);
	return 0;
}

static int method_index(const char *label)
{
	for (int i = 0; i < spec.method_count; i++)
		if (strcmp(spec.methods[i].label, label) == 0)
			return i;
	return -1;
}

static void run_pattern(enum aa_pattern2d_kind kind, double angle, double thickness, double *errors)
{
	struct aa_polygon2d polys[16];
	int n = aa_pattern2d_make(kind, angle, thickness, 0, SIZE, SIZE, polys);
	double coverage[SIZE * SIZE];
	aa_exact_coverage(polys, n, SIZE, SIZE, coverage);
	struct aa_scene *scene;
	struct aa_error err = {0};
	float fg[3] = {1, 1, 1}, bg[3] = {0, 0, 0};
	assert_int_equal(aa_scene_from_polygons(polys, n, SIZE, SIZE, fg, bg, &scene, &err), 0);
	const struct aa_job_spec *jobs[2] = {&single, &temporal};
	const int *indices[2] = {single_index, temporal_index};
	for (int j = 0; j < 2; j++) {
		if (jobs[j]->method_count == 0)
			continue;
		struct capture c = {coverage, errors, indices[j], jobs[j]->frames - 1};
		fixture_free(fixture_run(jobs[j], scene, on_event, &c));
	}
	aa_scene_free(scene);
}

static int setup(void **state)
{
	(void)state;
	struct aa_error err = {0};
	if (fixture_setup(state))
		return -1;
	/* every registered method at its defaults, plus the other MSAA counts and the virtual 4x path */
	const char *extra[] = {"msaa:2", "msaa:8", "msaa:4,path=virtual", "ssaa:4"};
	const int extra_count = (int)(sizeof extra / sizeof extra[0]);
	aa_job_spec_defaults(&spec);
	spec.method_count = 0;
	spec.width = spec.height = SIZE;
	spec.frames = 1;
	spec.reference_samples = 2; /* the exact coverage is the reference here */
	for (int i = 0; i < aa_method_count + extra_count && spec.method_count < AA_MAX_METHODS; i++) {
		const char *text = i < aa_method_count ? aa_methods[i]->name : extra[i - aa_method_count];
		if (strcmp(text, "copy") == 0 || strcmp(text, "floor") == 0)
			continue; /* the benchmark floors, not AA methods */
		struct aa_method_spec *m = &spec.methods[spec.method_count];
		if (aa_method_parse(text, "methods", &m->method, &m->params, &err))
			return -1;
		aa_method_label(m->method, &m->params, m->label, sizeof m->label);
		if (method_index(m->label) < 0)
			spec.method_count++;
	}
	single = temporal = spec;
	single.method_count = temporal.method_count = 0;
	snprintf(temporal.path, sizeof temporal.path, "static");
	temporal.frames = TEMPORAL_FRAMES;
	for (int i = 0; i < spec.method_count; i++) {
		const struct aa_method *m = spec.methods[i].method;
		unsigned needs = m->needs_fn ? m->needs_fn(&spec.methods[i].params) : m->needs;
		struct aa_job_spec *to = (needs & AA_NEED_HISTORY) ? &temporal : &single;
		int *index = (needs & AA_NEED_HISTORY) ? temporal_index : single_index;
		index[to->method_count] = i;
		to->methods[to->method_count++] = spec.methods[i];
	}
	return 0;
}


static double mean_over(int m, int first_angle, int last_angle)
{
	double sum = 0;
	for (int a = first_angle; a <= last_angle; a++)
		sum += error_at[m][a];
	return sum / (last_angle - first_angle + 1);
}

static void test_half_planes(void **state)
{
	(void)state;
	double errors[AA_MAX_METHODS];
	for (int a = 0; a < ANGLES; a++) {
		run_pattern(AA_PATTERN2D_HALF_PLANE, 5.0 * a, 0, errors);
		for (int m = 0; m < spec.method_count; m++)
			error_at[m][a] = errors[m];
	}
	printf("  mean abs coverage error, half-plane through the centre of a %dx%d image (temporal methods: "
	       "frame %d of a static view):\n  %-22s", SIZE, SIZE, TEMPORAL_FRAMES, "method \\ degrees");
	for (int a = 0; a < ANGLES; a += 2)
		printf(" %6d", 5 * a);
	printf("   mean\n");
	for (int m = 0; m < spec.method_count; m++) {
		printf("  %-22s", spec.methods[m].label);
		for (int a = 0; a < ANGLES; a += 2)
			printf(" %6.4f", error_at[m][a]);
		printf(" %6.4f\n", mean_over(m, 0, ANGLES - 1));
	}
	int none = method_index("none");
	assert_true(none >= 0);
	for (int m = 0; m < spec.method_count; m++)
		if (m != none && !(mean_over(m, 0, ANGLES - 1) < mean_over(none, 0, ANGLES - 1)))
			fail_msg("%s does not beat none on half-planes (%.4f vs %.4f)", spec.methods[m].label,
				 mean_over(m, 0, ANGLES - 1), mean_over(none, 0, ANGLES - 1));
	/* near-horizontal edges (5 and 10 degrees): the post-process search is hardest there */
	int fxaa = method_index("fxaa");
	const char *better[] = {"msaa:8", "smaa"};
	for (size_t b = 0; fxaa >= 0 && b < 2; b++) {
		int m = method_index(better[b]);
		if (m < 0)
			continue;
		printf("  near-horizontal (5-10 deg): %s %.4f vs fxaa %.4f\n", better[b], mean_over(m, 1, 2),
		       mean_over(fxaa, 1, 2));
		assert_true(mean_over(m, 1, 2) < mean_over(fxaa, 1, 2));
	}
}

/* A bar 0.5 px wide: single-sample post-process methods only see the pixels the bar happened to cover,
 * so they cannot restore the missing ones; that is expected, and reported here. Methods that take more
 * geometric samples must beat none. */
static void test_thin_bar(void **state)
{
	(void)state;
	double sum[AA_MAX_METHODS] = {0};
	const double angles[] = {3.0, 20.0, 37.0, 60.0};
	for (size_t a = 0; a < sizeof angles / sizeof angles[0]; a++) {
		double errors[AA_MAX_METHODS];
		run_pattern(AA_PATTERN2D_BAR, angles[a], 0.5, errors);
		for (int m = 0; m < spec.method_count; m++)
			sum[m] += errors[m] / 4.0;
	}
	int none = method_index("none");
	printf("  bar 0.5 px wide, mean over 3/20/37/60 degrees:\n");
	for (int m = 0; m < spec.method_count; m++) {
		bool loses = m != none && sum[m] >= sum[none];
		printf("  %-22s %.4f%s\n", spec.methods[m].label, sum[m],
		       loses ? "  loses the thin bar (no more geometric samples than none)" : "");
		unsigned needs = spec.methods[m].method->needs;
		if (needs & (AA_NEED_MSAA | AA_NEED_SUPERSAMPLED | AA_NEED_SUBSAMPLES))
			assert_true(sum[m] < sum[none]);
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_half_planes),
		cmocka_unit_test(test_thin_bar),
	};
	return fixture_status(cmocka_run_group_tests(tests, setup, fixture_teardown));
}
