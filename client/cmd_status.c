/* aalab status: shows one job on aalabd: its state, progress and, once done, each method's cost and
 * accuracy. */
#include <stdio.h>
#include <string.h>

#include "client.h"

static const char status_help[] =
	"usage: aalab status JOB [--connect ADDRESS] [--json]\n"
	"\n"
	"Shows a job's state and progress; once it is done, each method's GPU ms (median, p10-p90, n), memory,\n"
	"PSNR, SSIM and alpha rule.\n";

static void print_summary(json_t *summary)
{
	size_t i;
	json_t *m;
	json_array_foreach(summary, i, m) {
		json_t *psnr = json_object_get(m, "psnr");
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
	int rc = aa_service_args("status", status_help, argc, argv, &a);
	if (rc)
		return rc > 0 ? AA_EXIT_OK : AA_EXIT_USAGE;
	if (!a.job) {
		fputs(status_help, stderr);
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
			json_t *spec = json_object_get(job, "spec"), *e = json_object_get(job, "error");
			printf("job %s: %s, %lld of %lld frames done\n", json_string_value(json_object_get(job, "id")),
			       json_string_value(json_object_get(job, "state")), json_integer_value(json_object_get(job, "done")),
			       json_integer_value(json_object_get(job, "total")));
			printf("  scene %s, %s, %lld frames\n", json_string_value(json_object_get(spec, "scene")),
			       json_string_value(json_object_get(spec, "size")), json_integer_value(json_object_get(spec, "frames")));
			if (e)
				printf("  error: %s\n", json_string_value(json_object_get(e, "message")));
			print_summary(json_object_get(job, "summary"));
		}
	}
	json_decref(r);
	aa_conn_close(conn);
	return status;
}
