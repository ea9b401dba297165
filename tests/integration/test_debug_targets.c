/* Job option debug_targets: every intermediate image of a method is read back after each frame.
 * taa filters NaN/Inf out of what it blends (its output stays finite when the scene pass is poisoned), so
 * only the readback of its intermediates shows that its scene target held them; a clean run reads the
 * same targets and finds none; the `finite` verdict counts what the readback found. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "run/engine.h"
#include "fixture.h"
#include "results/results.h"
#include "results/verdicts.h"

#define FRAMES 3
#define POISONED_FRAME 1

/* taa-sobel's sobel targets are R16F images whose layout the readback must give back as it found it */
static const char *const methods[] = {"taa", "taa-sobel"};
#define METHODS 2

static struct aa_job_result *run(bool debug_targets, bool poison)
{
	struct aa_job_spec spec;
	fixture_spec(&spec, "thin-wires", methods, METHODS, 64, 36, FRAMES, 4);
	snprintf(spec.path, sizeof spec.path, "static");
	spec.debug_targets = debug_targets;
	spec.inject_nonfinite_frame = poison ? POISONED_FRAME : -1;
	struct aa_job_result *r = fixture_run(&spec, NULL, NULL, NULL);
	/* checked here, not only at teardown: cmocka 1.1 reports a failed group teardown with exit status 0,
	 * and the readback's barriers and copies are what validation would object to */
	assert_int_equal(aa_engine_validation_errors(fixture_engine), 0);
	return r;
}

/* results.json's frames[f].intermediates of the job's first method, or NULL (the caller frees *root). */
static json_t *intermediates_json(const struct aa_job_result *r, int f, json_t **root)
{
	*root = aa_results_to_json(r);
	json_t *method = json_array_get(json_object_get(*root, "methods"), 0);
	return json_object_get(json_array_get(json_object_get(method, "frames"), (size_t)f), "intermediates");
}

static enum aa_verdict_state finite_verdict(const struct aa_job_result *r, int m)
{
	struct aa_verdict v;
	aa_verdict_judge(r, m, &v);
	return v.state[AA_VERDICT_FINITE];
}

/* Without the option the poisoned frame goes unnoticed: the output is finite and nothing is read back. */
static void test_option_off_sees_only_the_output(void **state)
{
	(void)state;
	struct aa_job_result *r = run(false, true);
	for (int m = 0; m < METHODS; m++) {
		for (int f = 0; f < FRAMES; f++) {
			const struct aa_frame_result *fr = &r->methods[m].frames[f];
			assert_int_equal(fr->nonfinite, 0);
			assert_int_equal(fr->targets_read, 0);
			assert_int_equal(fr->intermediate_invalid, 0);
		}
		assert_int_equal(finite_verdict(r, m), AA_VERDICT_PASS);
	}
	json_t *root;
	assert_null(intermediates_json(r, POISONED_FRAME, &root)); /* results.json has no intermediates */
	json_decref(root);
	fixture_free(r);
}

/* Method m of a poisoned run with the option on: its scene target is named in the poisoned frame only,
 * and its output is finite throughout. */
static void check_poisoned(const struct aa_job_result *r, int m)
{
	for (int f = 0; f < FRAMES; f++) {
		const struct aa_frame_result *fr = &r->methods[m].frames[f];
		printf("  %s frame %d: %d targets read, %ld invalid texels, output %ld NaN/Inf", methods[m], f,
		       fr->targets_read, fr->intermediate_invalid, fr->nonfinite);
		for (int k = 0; k < fr->invalid_target_count; k++)
			printf(", %s: %ld", fr->invalid_targets[k].name, fr->invalid_targets[k].texels);
		printf("\n");
		assert_int_equal(fr->nonfinite, 0);
		assert_true(fr->targets_read >= 2); /* the scene target's colour and the history at least */
		if (f != POISONED_FRAME) {
			assert_int_equal(fr->intermediate_invalid, 0);
			assert_int_equal(fr->invalid_target_count, 0);
			continue;
		}
		assert_true(fr->intermediate_invalid > 0);
		assert_true(fr->invalid_target_count >= 1);
		bool scene_colour = false;
		long named = 0;
		for (int k = 0; k < fr->invalid_target_count; k++) {
			scene_colour |= strstr(fr->invalid_targets[k].name, "colour") != NULL;
			named += fr->invalid_targets[k].texels;
		}
		assert_true(scene_colour);
		assert_int_equal(named, fr->intermediate_invalid);
		/* the poison pattern is 2 pixels of every 11: no more than that share of a target */
		assert_true(fr->intermediate_invalid <= (long)fr->invalid_target_count * (2 * 64 * 36 / 11 + 36));
	}
	assert_int_equal(finite_verdict(r, m), AA_VERDICT_FAIL);
}

/* With it the poisoned frame's scene target is named, the output is still finite, and the frame after
 * (history included) is clean again. */
static void test_option_on_catches_the_intermediate(void **state)
{
	(void)state;
	struct aa_job_result *r = run(true, true);
	for (int m = 0; m < METHODS; m++)
		check_poisoned(r, m);
	/* results.json says the same: the count and the target's name */
	const struct aa_frame_result *fr = &r->methods[0].frames[POISONED_FRAME];
	json_t *root, *in = intermediates_json(r, POISONED_FRAME, &root);
	assert_non_null(in);
	assert_int_equal(json_integer_value(json_object_get(in, "targets_read")), fr->targets_read);
	assert_int_equal(json_integer_value(json_object_get(in, "invalid_texels")), fr->intermediate_invalid);
	json_t *first = json_array_get(json_object_get(in, "invalid_targets"), 0);
	assert_string_equal(json_string_value(json_object_get(first, "name")), fr->invalid_targets[0].name);
	assert_int_equal(json_integer_value(json_object_get(first, "invalid_texels")), fr->invalid_targets[0].texels);
	json_decref(root);
	fixture_free(r);
}

/* A clean run reads every target back and finds nothing. */
static void test_clean_run_reports_zero(void **state)
{
	(void)state;
	struct aa_job_result *r = run(true, false);
	for (int m = 0; m < METHODS; m++) {
		for (int f = 0; f < FRAMES; f++) {
			const struct aa_frame_result *fr = &r->methods[m].frames[f];
			assert_true(fr->targets_read >= 2);
			assert_int_equal(fr->intermediate_invalid, 0);
			assert_int_equal(fr->nonfinite, 0);
		}
		assert_int_equal(finite_verdict(r, m), AA_VERDICT_PASS);
	}
	fixture_free(r);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_option_off_sees_only_the_output),
		cmocka_unit_test(test_option_on_catches_the_intermediate),
		cmocka_unit_test(test_clean_run_reports_zero),
	};
	return fixture_status(cmocka_run_group_tests(tests, fixture_setup, fixture_teardown));
}
