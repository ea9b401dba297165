/* Runs a job's cases one after another (docs/job-format.md, "Suites"): each case is an
 * ordinary run of aa_job_run_scene, its events tagged with the case and its progress counted over the
 * whole job. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "run/engine_internal.h"
#include "run/farm.h"
#include "run/job_spec.h"

struct suite_relay {
	aa_event_fn on_event;
	void *user;
	int case_index;
	long done_before, total; /* units of the cases before this one, and of the whole job */
};

static int relay(const struct aa_event *ev, void *user)
{
	struct suite_relay *r = user;
	if (!r->on_event)
		return 0;
	struct aa_event out = *ev;
	out.case_index = r->case_index;
	if (ev->type == AA_EVENT_PROGRESS) {
		out.done = (int)(r->done_before + ev->done);
		out.total = (int)r->total;
	}
	return r->on_event(&out, r->user);
}

static long case_units(const struct aa_job_spec *c)
{
	return (long)c->frames * (1 + (long)c->method_count * c->timing_repeat);
}

long aa_suite_total_units(const struct aa_job_spec *spec)
{
	long total = 0;
	for (int i = 0; i < aa_job_case_count(spec); i++) {
		struct aa_job_spec c;
		aa_job_case(spec, i, &c);
		total += case_units(&c);
	}
	return total;
}

void aa_suite_result_free(struct aa_suite_result *r)
{
	if (!r)
		return;
	for (int i = 0; i < r->case_count && i < AA_MAX_CASES; i++) {
		aa_job_result_free(r->cases[i]);
		free(r->cases[i]);
	}
	free(r);
}

int aa_suite_run(struct aa_engine *engine, const struct aa_job_spec *spec, aa_scene_source_fn scenes,
		 void *scene_user, aa_event_fn on_event, void *user, struct aa_suite_result **out,
		 struct aa_error *err)
{
	double t0 = aa_now_ms();
	struct aa_suite_result *r = calloc(1, sizeof *r);
	struct aa_job_spec *c = malloc(sizeof *c);
	if (!r || !c) {
		free(r);
		free(c);
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	}
	r->spec = *spec;
	time_t now = time(NULL);
	struct tm tm;
	gmtime_r(&now, &tm);
	strftime(r->started_at, sizeof r->started_at, "%Y-%m-%dT%H:%M:%SZ", &tm);
	struct suite_relay relay_state = {.on_event = on_event, .user = user, .total = aa_suite_total_units(spec)};
	int rc = 0;
	for (int i = 0; rc == 0 && i < aa_job_case_count(spec); i++) {
		aa_job_case(spec, i, c);
		relay_state.case_index = i;
		const struct aa_scene *scene = NULL;
		if (scenes && !(scene = scenes(c, scene_user, err))) {
			rc = -1;
		} else {
			rc = aa_job_run_scene(engine, c, scene, relay, &relay_state, &r->cases[i], err);
		}
		if (rc == 0) {
			r->case_count = i + 1;
			relay_state.done_before += case_units(c);
		} else if (spec->is_suite && err->code != AA_ERR_CANCELLED) {
			char id[512];
			aa_case_id(spec, i, id, sizeof id);
			aa_error_prefix(err, "case %s", id);
			/* the case's own field paths ("path", "scene") become the suite's */
			if (!strcmp(err->path, "scene") || !strcmp(err->path, "path")) {
				char field[8];
				snprintf(field, sizeof field, "%.7s", err->path);
				snprintf(err->path, sizeof err->path, "cases[%d].%s", i, field);
			}
		}
	}
	free(c);
	r->wall_seconds = (aa_now_ms() - t0) / 1000.0;
	if (rc) {
		aa_suite_result_free(r);
		return -1;
	}
	*out = r;
	return 0;
}
