/* Shared set-up of the GPU integration tests (see fixture.h). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <cmocka.h>
#include <math.h>

#include "fixture.h"
#include "methods/methods.h"
#include "run/job_spec.h"
#include "scene/scene.h"

struct aa_engine *fixture_engine;
static int validation_failures; /* set by fixture_teardown, read by fixture_status */

int fixture_setup(void **state)
{
	(void)state;
	struct aa_error err = {0};
	struct aa_engine_options o = {.validation = aa_env_flag("AALAB_VALIDATION")};
	if (aa_engine_create(&o, &fixture_engine, &err)) {
		fprintf(stderr, "engine: %s\n", err.message);
		return -1;
	}
	return 0;
}

int fixture_teardown(void **state)
{
	(void)state;
	int errors = aa_engine_validation_errors(fixture_engine);
	aa_engine_destroy(fixture_engine);
	if (errors) {
		fprintf(stderr, "%d Vulkan validation errors\n", errors);
		validation_failures++;
	}
	return errors ? -1 : 0;
}

int fixture_status(int cmocka_status)
{
	return cmocka_status || validation_failures ? 1 : 0;
}

void fixture_spec(struct aa_job_spec *spec, const char *scene, const char *const *methods, int n, int width,
		  int height, int frames, int reference_samples)
{
	aa_job_spec_defaults(spec);
	if (scene)
		snprintf(spec->scene, sizeof spec->scene, "%s", scene);
	spec->width = width;
	spec->height = height;
	spec->frames = frames;
	spec->reference_samples = reference_samples;
	spec->method_count = n;
	for (int i = 0; i < n; i++) {
		struct aa_error err = {0};
		char path[32];
		snprintf(path, sizeof path, "methods[%d]", i);
		if (aa_method_parse(methods[i], path, &spec->methods[i].method, &spec->methods[i].params, &err))
			fail_msg("%s: %s", methods[i], err.message);
		aa_method_label(spec->methods[i].method, &spec->methods[i].params, spec->methods[i].label,
				sizeof spec->methods[i].label);
	}
}

struct aa_job_result *fixture_run(const struct aa_job_spec *spec, const struct aa_scene *scene, aa_event_fn fn,
				  void *user)
{
	struct aa_job_result *r = NULL;
	struct aa_error err = {0};
	if (aa_job_run_scene(fixture_engine, spec, scene, fn, user, &r, &err))
		fail_msg("job failed: %s: %s", err.path, err.message);
	return r;
}

void fixture_free(struct aa_job_result *r)
{
	aa_job_result_free(r);
	free(r);
}

struct coverage_capture {
	const double *coverage;
	int size;
	float *none;
	struct fixture_coverage out;
};

static int on_coverage_frame(const struct aa_event *ev, void *user)
{
	struct coverage_capture *c = user;
	if (ev->type != AA_EVENT_METHOD_FRAME || ev->method_index > 1)
		return 0;
	const float *px = ev->linear->pixels;
	int n = c->size * c->size;
	double sum = 0;
	for (int i = 0; i < n; i++)
		sum += fabs(px[i * 4] - c->coverage[i]);
	c->out.error[ev->method_index] = sum / n;
	for (int i = 0; i < n; i++) {
		if (ev->method_index == 0) {
			c->none[i] = px[i * 4];
			continue;
		}
		double d = fabs(px[i * 4] - c->none[i]);
		c->out.max_change = d > c->out.max_change ? d : c->out.max_change;
		c->out.brighter += px[i * 4] > c->none[i] + 1e-3;
		c->out.darker += px[i * 4] < c->none[i] - 1e-3;
	}
	return 0;
}

struct fixture_coverage fixture_pattern_coverage(enum aa_pattern2d_kind pattern, double angle, const char *method,
						 int size)
{
	double *coverage = calloc((size_t)size * size, sizeof *coverage);
	float *none = calloc((size_t)size * size, sizeof *none);
	assert_non_null(coverage);
	assert_non_null(none);
	struct aa_polygon2d polys[16];
	int n = aa_pattern2d_make(pattern, angle, 0, 0, size, size, polys);
	aa_exact_coverage(polys, n, size, size, coverage);
	struct aa_scene *scene;
	struct aa_error err = {0};
	float fg[3] = {1, 1, 1}, bg[3] = {0, 0, 0};
	assert_int_equal(aa_scene_from_polygons(polys, n, size, size, fg, bg, &scene, &err), 0);
	const char *methods[] = {"none", method};
	struct aa_job_spec spec;
	fixture_spec(&spec, "pattern", methods, 2, size, size, 1, 2);
	struct coverage_capture c = {.coverage = coverage, .size = size, .none = none};
	fixture_free(fixture_run(&spec, scene, on_coverage_frame, &c));
	aa_scene_free(scene);
	free(coverage);
	free(none);
	return c.out;
}
