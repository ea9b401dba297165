/* Timings as distributions: methods interleave frame by frame in an order that rotates, so
 * that no method always runs first after the reference; timing.repeat re-times each method's frame
 * without scoring it again, and never advances a method's history: the scored images of methods with
 * history are the same with and without repeats. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "run/engine.h"
#include "fixture.h"
#include "results/results.h"

/* No method keeps one place in the order: over as many frames as methods, each takes every place. */
static void test_order_rotates(void **state)
{
	(void)state;
	const char *methods[] = {"none", "fxaa", "msaa:4"};
	struct aa_job_spec spec;
	fixture_spec(&spec, "hard-edges", methods, 3, 64, 36, 3, 2);
	struct aa_job_result *r = fixture_run(&spec, NULL, NULL, NULL);
	for (int m = 0; m < 3; m++) {
		unsigned places = 0;
		assert_int_equal(r->methods[m].timed_count, 3);
		for (int i = 0; i < r->methods[m].timed_count; i++)
			places |= 1u << r->methods[m].timed[i].position;
		printf("  %-8s places by frame: %d %d %d\n", methods[m], r->methods[m].timed[0].position,
		       r->methods[m].timed[1].position, r->methods[m].timed[2].position);
		assert_int_equal(places, 7u);
	}
	fixture_free(r);
}

/* timing.repeat: frames x repeat timed renders per method, each with its passes; repeats rotate too. */
static void test_repeat_counts_every_render(void **state)
{
	(void)state;
	const char *methods[] = {"none", "smaa", "taa"};
	struct aa_job_spec spec;
	fixture_spec(&spec, "hard-edges", methods, 3, 64, 36, 2, 2);
	spec.timing_repeat = 4;
	struct aa_job_result *r = fixture_run(&spec, NULL, NULL, NULL);
	for (int m = 0; m < 3; m++) {
		const struct aa_method_result *mr = &r->methods[m];
		struct aa_method_summary s;
		aa_method_summarize(mr, &s);
		assert_int_equal(mr->timed_count, 8);
		assert_int_equal(s.gpu_ms.n, 8);
		assert_true(s.gpu_ms.min <= s.gpu_ms.p10 && s.gpu_ms.p10 <= s.gpu_ms.median &&
			    s.gpu_ms.median <= s.gpu_ms.p90);
		unsigned places = 0;
		for (int i = 0; i < mr->timed_count; i++) {
			assert_int_equal(mr->timed[i].ordinal, i / 4);
			assert_int_equal(mr->timed[i].repeat, i % 4);
			assert_int_equal(mr->timed[i].pass_count, mr->frames[i / 4].pass_count);
			places |= 1u << mr->timed[i].position;
		}
		assert_int_equal(places, 7u);
		for (int k = 0; k < mr->frames[0].pass_count; k++) {
			struct aa_timing_stats t;
			aa_pass_timing_stats(mr, mr->frames[0].passes[k].name, &t);
			assert_int_equal(t.n, 8);
		}
		printf("  %-5s GPU ms median %.2f, p10-p90 %.2f-%.2f, min %.2f, n %d\n", mr->label, s.gpu_ms.median,
		       s.gpu_ms.p10, s.gpu_ms.p90, s.gpu_ms.min, s.gpu_ms.n);
	}
	fixture_free(r);
}

#define HISTORY_METHODS 4
#define HISTORY_FRAMES 4

static int hash_images(const struct aa_event *ev, void *user)
{
	uint64_t (*h)[HISTORY_FRAMES] = user;
	if (ev->type != AA_EVENT_METHOD_FRAME)
		return 0;
	uint64_t v = 14695981039346656037ull;
	for (size_t i = 0; i < (size_t)ev->image->width * ev->image->height * 4; i++)
		v = (v ^ ev->image->pixels[i]) * 1099511628211ull;
	h[ev->method_index][ev->frame_ordinal] = v;
	return 0;
}

/* A repeat must not advance history: with 3 repeats, every scored frame of taa, t2msaa and asaa is the
 * image they give without repeats, on a moving scene (msaa, without history, as a control). */
static void test_repeats_leave_history_alone(void **state)
{
	(void)state;
	const char *methods[HISTORY_METHODS] = {"taa", "t2msaa", "asaa", "msaa:4"};
	uint64_t once[HISTORY_METHODS][HISTORY_FRAMES] = {{0}}, repeated[HISTORY_METHODS][HISTORY_FRAMES] = {{0}};
	struct aa_job_spec spec;
	fixture_spec(&spec, "moving-sphere", methods, HISTORY_METHODS, 96, 54, HISTORY_FRAMES, 2);
	fixture_free(fixture_run(&spec, NULL, hash_images, once));
	spec.timing_repeat = 3;
	fixture_free(fixture_run(&spec, NULL, hash_images, repeated));
	for (int m = 0; m < HISTORY_METHODS; m++)
		for (int f = 0; f < HISTORY_FRAMES; f++) {
			if (once[m][f] != repeated[m][f])
				fail_msg("%s frame %d differs with repeats: history advanced", methods[m], f);
		}
	printf("  taa, t2msaa, asaa, msaa:4: %d frames identical with and without 3 repeats\n", HISTORY_FRAMES);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_order_rotates),
		cmocka_unit_test(test_repeat_counts_every_render),
		cmocka_unit_test(test_repeats_leave_history_alone),
	};
	return fixture_status(cmocka_run_group_tests(tests, fixture_setup, fixture_teardown));
}
