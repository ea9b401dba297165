/* aalab status: shows one job on aalabd: its state, progress and, once done, each method's cost and
 * accuracy. */
#include <stdio.h>
#include <string.h>

#include "client.h"

const char aa_status_help[] =
	"usage: aalab status JOB [options]\n"
	"\n"
	"Shows a job on aalabd: once it is done, its verdict first (the methods on the cost-quality front,\n"
	"ties, what beats each other method); then its state and renders done, scene or suite, labels, the\n"
	"comparison with its baseline (held or tripped), each method's GPU ms (median, p10-p90, n), memory,\n"
	"PSNR, SSIM and alpha rule, and last the warnings, each with what to do.\n"
	"\n"
	"  --json                  print the daemon's record of the job as JSON instead\n"
	AA_CONNECT_OPTIONS_HELP
	"\n"
	"Exit status: 0 shown, 1 the daemon could not be reached, 2 unknown job.\n";

/* A string field, or fallback when it is missing. */
static const char *text_of(json_t *o, const char *key, const char *fallback)
{
	const char *s = json_string_value(json_object_get(o, key));
	return s ? s : fallback;
}

static void print_summary(json_t *summary)
{
	size_t i;
	json_t *m;
	json_array_foreach(summary, i, m) {
		json_t *psnr = json_object_get(m, "psnr");
		const char *case_id = json_string_value(json_object_get(m, "case"));
		if (case_id && (i == 0 || strcmp(case_id, text_of(json_array_get(summary, i - 1), "case", ""))))
			printf("  case %s\n", case_id); /* a suite's summary runs case by case */
		char psnr_text[32];
		if (json_is_number(psnr))
			snprintf(psnr_text, sizeof psnr_text, "%.2f dB", json_number_value(psnr));
		else
			snprintf(psnr_text, sizeof psnr_text, "identical");
		/* the GPU time's spread and count, and the alpha rule, when the daemon's summary has them */
		char spread[64] = "";
		if (json_is_number(json_object_get(m, "gpu_ms_p10")) && json_is_number(json_object_get(m, "gpu_ms_p90")))
			snprintf(spread, sizeof spread, " (p10-p90 %.2f-%.2f, n %lld)",
				 json_number_value(json_object_get(m, "gpu_ms_p10")),
				 json_number_value(json_object_get(m, "gpu_ms_p90")),
				 (long long)json_integer_value(json_object_get(m, "gpu_ms_n")));
		const char *alpha = json_string_value(json_object_get(m, "alpha_rule"));
		printf("  %-24s %9.3f ms%s %8.2f MB  PSNR %-10s SSIM %.4f%s%s\n",
		       json_string_value(json_object_get(m, "label")), json_number_value(json_object_get(m, "gpu_ms")),
		       spread, json_number_value(json_object_get(m, "memory_bytes")) / 1048576.0, psnr_text,
		       json_number_value(json_object_get(m, "ssim")), alpha ? "  alpha " : "", alpha ? alpha : "");
	}
}

int cmd_status(int argc, char **argv)
{
	struct aa_service_args a;
	int rc = aa_service_args("status", aa_status_help, argc, argv, &a);
	if (rc)
		return rc > 0 ? AA_EXIT_OK : AA_EXIT_USAGE;
	if (!a.job) {
		fputs(aa_status_help, stderr);
		return AA_EXIT_USAGE;
	}
	struct aa_conn *conn;
	char err[1200];
	if (aa_conn_open(a.connect, &conn, err, sizeof err)) {
		fprintf(stderr, "aalab status: %s\n", err);
		return AA_EXIT_FAILED;
	}
	json_t *msg = json_pack("{ss ss}", "op", "status", "job", a.job);
	json_t *r = aa_conn_request(conn, msg, NULL, NULL);
	json_decref(msg);
	int status = aa_reply_status("status", r);
	if (status == AA_EXIT_OK) {
		json_t *job = json_object_get(r, "job");
		if (a.json) {
			json_dumpf(job, stdout, JSON_INDENT(2));
			fputc('\n', stdout);
		} else {
			/* a finished job: its verdict first, as results.json says it; its warnings last */
			json_t *results = !strcmp(text_of(job, "state", ""), "done") ? aa_job_results(conn, a.job) : NULL;
			if (results)
				aa_print_verdict(results, stdout);
			json_t *spec = json_object_get(job, "spec"), *e = json_object_get(job, "error");
			printf("job %s: %s, %lld of %lld renders done\n", json_string_value(json_object_get(job, "id")),
			       json_string_value(json_object_get(job, "state")), json_integer_value(json_object_get(job, "done")),
			       json_integer_value(json_object_get(job, "total")));
			if (json_object_get(spec, "cases"))
				printf("  suite %s, %zu cases\n", text_of(spec, "suite", ""),
				       json_array_size(json_object_get(spec, "cases")));
			else
				printf("  scene %s, %s, %lld frames\n", json_string_value(json_object_get(spec, "scene")),
				       json_string_value(json_object_get(spec, "size")),
				       json_integer_value(json_object_get(spec, "frames")));
			const char *key;
			json_t *v, *cmp = json_object_get(job, "compare");
			json_object_foreach(json_object_get(spec, "labels"), key, v)
				printf("  label %s=%s\n", key, json_string_value(v));
			if (cmp) { /* the comparison with the job's baseline: its gates held or tripped */
				json_t *counts = json_object_get(cmp, "counts"), *t;
				size_t k;
				printf("  baseline %s (job %s): %s", json_string_value(json_object_get(cmp, "baseline")),
				       text_of(cmp, "job", "-"),
				       json_string_value(json_object_get(cmp, "verdict")));
				if (counts)
					printf(", %lld of %lld gates tripped", json_integer_value(json_object_get(counts, "tripped")),
					       json_integer_value(json_object_get(counts, "gates")));
				if (json_object_get(cmp, "message"))
					printf(": %s", json_string_value(json_object_get(cmp, "message")));
				putchar('\n');
				json_array_foreach(json_object_get(cmp, "tripped"), k, t)
					printf("    tripped: %s %s: %s\n", json_string_value(json_object_get(t, "case")),
					       json_string_value(json_object_get(t, "method")),
					       json_string_value(json_object_get(t, "message")));
			}
			if (e)
				printf("  error: %s\n", json_string_value(json_object_get(e, "message")));
			print_summary(json_object_get(job, "summary"));
			if (results)
				aa_print_warnings(results, stdout);
			json_decref(results);
		}
	}
	json_decref(r);
	aa_conn_close(conn);
	return status;
}
