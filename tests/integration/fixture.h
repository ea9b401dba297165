/* Shared set-up of the GPU integration tests: one engine per test program (validation on when
 * $AALAB_VALIDATION is on, aa_env_flag; teardown fails on any validation error), job specs from method
 * strings, and job runs that fail the test with the engine's message. */
#ifndef AA_TEST_FIXTURE_H
#define AA_TEST_FIXTURE_H

#include "reference/exact_coverage.h"
#include "run/engine.h"

extern struct aa_engine *fixture_engine;

int fixture_setup(void **state);
int fixture_teardown(void **state);
/* cmocka 1.1 returns 0 when a group teardown fails, so the validation errors fixture_teardown finds
 * would not fail the program: main returns fixture_status(cmocka_run_group_tests(...)). */
int fixture_status(int cmocka_status);
/* A job of `n` methods (strings as on the command line) on a scene name, default path, from frame 0. */
void fixture_spec(struct aa_job_spec *spec, const char *scene, const char *const *methods, int n, int width,
		  int height, int frames, int reference_samples);
/* Runs a job (scene NULL: load spec->scene); fails the current test when the job fails. */
struct aa_job_result *fixture_run(const struct aa_job_spec *spec, const struct aa_scene *scene, aa_event_fn fn,
				  void *user);
void fixture_free(struct aa_job_result *r);

/* `none` and `method` on a white-on-black 2D pattern (size x size, one frame) against its exact coverage. */
struct fixture_coverage {
	double error[2];      /* mean |red - exact coverage| of none and of the method */
	double max_change;    /* largest |method - none| */
	int brighter, darker; /* pixels the method made brighter / darker than none by more than 1e-3 */
};
struct fixture_coverage fixture_pattern_coverage(enum aa_pattern2d_kind pattern, double angle, const char *method,
						 int size);

#endif
