/* aalab list: lists the jobs aalabd knows, oldest first, optionally only those in one state. */
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "client.h"

static const char list_help[] =
	"usage: aalab list [--state queued|running|done|failed|cancelled] [--connect ADDRESS] [--json]\n"
	"\n"
	"Lists the jobs aalabd holds: id, state, progress, scene and methods.\n";

int cmd_jobs(int argc, char **argv)
{
	struct aa_service_args a;
	int rc = aa_service_args("list", list_help, argc, argv, &a);
	if (rc)
		return rc > 0 ? AA_EXIT_OK : AA_EXIT_USAGE;
	if (a.job) {
		fprintf(stderr, "aalab list: unexpected argument '%s'\n", a.job);
		return AA_EXIT_USAGE;
	}
	struct aa_conn *conn;
	char err[1200];
	if (aa_conn_open(a.connect, &conn, err, sizeof err)) {
		fprintf(stderr, "aalab list: %s\n", err);
		return AA_EXIT_FAILED;
	}
	json_t *msg = json_pack("{ss}", "op", "list");
	if (a.state)
		json_object_set_new(msg, "state", json_string(a.state));
	json_t *r = aa_conn_request(conn, msg, NULL, NULL);
	json_decref(msg);
	int status = aa_reply_status("list", r);
	if (status == AA_EXIT_OK && a.json) {
		json_dumpf(json_object_get(r, "jobs"), stdout, JSON_INDENT(2));
		fputc('\n', stdout);
	} else if (status == AA_EXIT_OK) {
		size_t i;
		json_t *job;
		printf("%-8s %-10s %-9s %-16s %s\n", "ID", "STATE", "DONE", "SCENE", "METHODS");
		json_array_foreach(json_object_get(r, "jobs"), i, job) {
			json_t *spec = json_object_get(job, "spec"), *m;
			char done[32], methods[256] = "";
			snprintf(done, sizeof done, "%lld/%lld", json_integer_value(json_object_get(job, "done")),
				 json_integer_value(json_object_get(job, "total")));
			size_t k;
			json_array_foreach(json_object_get(spec, "methods"), k, m) {
				const char *label = json_is_string(m) ? json_string_value(m)
								      : json_string_value(json_object_get(m, "name"));
				snprintf(methods + strlen(methods), sizeof methods - strlen(methods), "%s%s", k ? "," : "",
					 label ? label : "?");
			}
			printf("%-8s %-10s %-9s %-16s %s\n", json_string_value(json_object_get(job, "id")),
			       json_string_value(json_object_get(job, "state")), done,
			       json_string_value(json_object_get(spec, "scene")), methods);
		}
	}
	json_decref(r);
	aa_conn_close(conn);
	return status;
}
