/* aalab cancel: cancels a queued job at once, or a running job after the frame it is rendering, and prints
 * the state the job is then in. */
#include <stdio.h>
#include <string.h>

#include "client.h"

const char aa_cancel_help[] =
	"usage: aalab cancel JOB [options]\n"
	"\n"
	"Cancels a job on aalabd: a queued job at once, a running one after the frame it is rendering, and\n"
	"prints the state the job is then in (\"job 000042: cancelled\").\n"
	"\n"
	"  --no-wait               print the state at once, without waiting for a running job to stop\n"
	"                          (default: wait)\n"
	"  --json                  print the reply as JSON instead\n"
	AA_CONNECT_OPTIONS_HELP
	"\n"
	"Exit status: 0 cancelled, 1 the daemon could not be reached, 2 unknown job or one that has ended.\n";

/* A running job stops after the frame it is rendering: follows it until then (its events after `after`),
 * so that the state printed is the one the cancel led to. Returns the job's status reply. */
static json_t *wait_for_end(struct aa_conn *conn, const char *job, long long after)
{
	json_t *msg = json_pack("{ss ss sI ss}", "op", "watch", "job", job, "after", (json_int_t)after, "frames", "none");
	json_t *r = aa_conn_request(conn, msg, NULL, NULL);
	json_decref(msg);
	bool ok = json_is_true(json_object_get(r, "ok"));
	json_decref(r);
	for (json_t *ev; ok && (ev = aa_conn_read(conn, NULL, NULL));) {
		const char *type = json_string_value(json_object_get(ev, "event"));
		ok = !(type && !strcmp(type, "watch_end"));
		json_decref(ev);
	}
	msg = json_pack("{ss ss}", "op", "status", "job", job);
	r = aa_conn_request(conn, msg, NULL, NULL);
	json_decref(msg);
	return r;
}

int cmd_cancel(int argc, char **argv)
{
	struct aa_service_args a;
	int rc = aa_service_args("cancel", aa_cancel_help, argc, argv, &a);
	if (rc)
		return rc > 0 ? AA_EXIT_OK : AA_EXIT_USAGE;
	if (!a.job) {
		fputs(aa_cancel_help, stderr);
		return AA_EXIT_USAGE;
	}
	struct aa_conn *conn;
	char err[1200];
	if (aa_conn_open(a.connect, &conn, err, sizeof err)) {
		fprintf(stderr, "aalab cancel: %s\n", err);
		return AA_EXIT_FAILED;
	}
	json_t *msg = json_pack("{ss ss}", "op", "status", "job", a.job);
	json_t *before = aa_conn_request(conn, msg, NULL, NULL);
	json_decref(msg);
	int status = aa_reply_status("cancel", before);
	const long long events = json_integer_value(json_object_get(json_object_get(before, "job"), "events"));
	json_decref(before);
	json_t *r = NULL;
	if (status == AA_EXIT_OK) {
		msg = json_pack("{ss ss}", "op", "cancel", "job", a.job);
		r = aa_conn_request(conn, msg, NULL, NULL);
		json_decref(msg);
		status = aa_reply_status("cancel", r);
	}
	const char *state = json_string_value(json_object_get(r, "state"));
	if (status == AA_EXIT_OK && !a.no_wait && state && strcmp(state, "cancelled")) {
		json_t *after = wait_for_end(conn, a.job, events);
		json_t *job = json_object_get(after, "job");
		if (json_string_value(json_object_get(job, "state")))
			json_object_set(r, "state", json_object_get(job, "state"));
		json_decref(after);
	}
	if (status == AA_EXIT_OK && a.json) {
		json_dumpf(r, stdout, JSON_COMPACT);
		fputc('\n', stdout);
	} else if (status == AA_EXIT_OK) {
		printf("job %s: %s\n", a.job, json_string_value(json_object_get(r, "state")));
	}
	json_decref(r);
	aa_conn_close(conn);
	return status;
}
