/* aalab cancel: cancels a queued job at once, or a running job after the frame it is rendering. */
#include <stdio.h>

#include "client.h"

static const char cancel_help[] =
	"usage: aalab cancel JOB [--connect ADDRESS] [--json]\n"
	"\n"
	"Cancels a job: a queued job at once, a running one after its current frame.\n";

int cmd_cancel(int argc, char **argv)
{
	struct aa_service_args a;
	int rc = aa_service_args("cancel", cancel_help, argc, argv, &a);
	if (rc)
		return rc > 0 ? AA_EXIT_OK : AA_EXIT_USAGE;
	if (!a.job) {
		fputs(cancel_help, stderr);
		return AA_EXIT_USAGE;
	}
	struct aa_conn *conn;
	char err[1200];
	if (aa_conn_open(a.connect, &conn, err, sizeof err)) {
		fprintf(stderr, "aalab cancel: %s\n", err);
		return AA_EXIT_FAILED;
	}
	json_t *msg = json_pack("{ss ss}", "op", "cancel", "job", a.job);
	json_t *r = aa_conn_request(conn, msg, NULL, NULL);
	json_decref(msg);
	int status = aa_reply_status("cancel", r);
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
