/* aalab list: lists the jobs aalabd knows, oldest first, optionally only those in one state, with some
 * labels or of one suite. */
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "client.h"
#include "run/farm.h"

const char aa_list_help[] =
	"usage: aalab list [options]\n"
	"\n"
	"Lists the jobs aalabd holds, oldest first: id, state, renders done, scene (or suite), labels, the\n"
	"comparison with its baseline (held or tripped) and methods.\n"
	"\n"
	"  --state STATE           only jobs in STATE: queued, running, done, failed or cancelled (default: all)\n"
	"  --label KEY=VALUE       only jobs with this label; repeatable, all of them (default: any labels)\n"
	"  --suite NAME            only the jobs of suite NAME (default: any)\n"
	"  --json                  print the jobs as JSON instead\n"
	AA_CONNECT_OPTIONS_HELP
	"\n"
	"Exit status: 0 listed, 1 the daemon could not be reached, 2 bad arguments.\n";

int cmd_jobs(int argc, char **argv)
{
	struct aa_service_args a;
	int rc = aa_service_args("list", aa_list_help, argc, argv, &a);
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
	if (a.suite)
		json_object_set_new(msg, "suite", json_string(a.suite));
	if (a.label_count) {
		json_t *labels = json_object();
		for (int i = 0; i < a.label_count; i++) {
			struct aa_label label[1];
			int n = 0;
			struct aa_error e = {0};
			if (aa_label_parse(a.labels[i], label, &n, "label", &e)) {
				fprintf(stderr, "aalab list: --label: %s\n", e.message);
				json_decref(labels);
				json_decref(msg);
				aa_conn_close(conn);
				return AA_EXIT_USAGE;
			}
			json_object_set_new(labels, label[0].key, json_string(label[0].value));
		}
		json_object_set_new(msg, "labels", labels);
	}
	json_t *r = aa_conn_request(conn, msg, NULL, NULL);
	json_decref(msg);
	int status = aa_reply_status("list", r);
	if (status == AA_EXIT_OK && a.json) {
		json_dumpf(json_object_get(r, "jobs"), stdout, JSON_INDENT(2));
		fputc('\n', stdout);
	} else if (status == AA_EXIT_OK) {
		size_t i;
		json_t *job;
		printf("%-8s %-10s %-9s %-22s %-28s %-9s %s\n", "ID", "STATE", "DONE", "SCENE", "LABELS", "BASELINE",
		       "METHODS");
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
			char scene[64], labels[256] = "";
			json_t *cases = json_object_get(spec, "cases"), *v;
			const char *key;
			if (cases) /* a suite: its name and how many cases */
				snprintf(scene, sizeof scene, "%s (%zu cases)",
					 json_string_value(json_object_get(spec, "suite")) ? json_string_value(json_object_get(spec, "suite"))
											     : "suite", json_array_size(cases));
			else
				snprintf(scene, sizeof scene, "%s", json_string_value(json_object_get(spec, "scene")));
			json_object_foreach(json_object_get(spec, "labels"), key, v)
				snprintf(labels + strlen(labels), sizeof labels - strlen(labels), "%s%s=%s", labels[0] ? "," : "",
					 key, json_string_value(v));
			const char *verdict = json_string_value(json_object_get(json_object_get(job, "compare"), "verdict"));
			printf("%-8s %-10s %-9s %-22s %-28s %-9s %s\n", json_string_value(json_object_get(job, "id")),
			       json_string_value(json_object_get(job, "state")), done, scene, labels[0] ? labels : "-",
			       verdict ? verdict : "-", methods);
		}
	}
	json_decref(r);
	aa_conn_close(conn);
	return status;
}
