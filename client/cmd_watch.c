/* aalab watch: follows a job on aalabd, from the start or after a given event, until it ends. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "client.h"

const char aa_watch_help[] =
	"usage: aalab watch JOB [options]\n"
	"\n"
	"Follows a job on aalabd until it ends: a progress bar on a terminal (renders done, time so far and\n"
	"an ETA), one line per event otherwise, then a last line with the job's state, its wall time, where\n"
	"its results are and the verdict.\n"
	"\n"
	"  --after SEQ             resume after event SEQ (default 0: from the start)\n"
	"  --json                  print the events as JSON lines instead\n"
	"  --quiet                 print nothing; only the exit status tells\n"
	AA_CONNECT_OPTIONS_HELP
	"\n"
	"Exit status: 0 the job is done, 1 it failed or was cancelled, 2 bad arguments or unknown job.\n";

static void print_number(const char *what, json_t *v, const char *unit)
{
	if (json_is_number(v))
		printf(" %s %.4g%s", what, json_number_value(v), unit);
	else if (v)
		printf(" %s -", what);
}

/* One plain line per event, for logs and pipes. */
static void print_event(json_t *ev)
{
	const char *type = json_string_value(json_object_get(ev, "event"));
	long long seq = json_integer_value(json_object_get(ev, "seq"));
	const char *case_id = json_string_value(json_object_get(ev, "case")); /* a suite's events name their case */
	if (!strcmp(type, "job_started")) {
		printf("%lld started on %s: scene %s", seq, json_string_value(json_object_get(ev, "device")),
		       json_string_value(json_object_get(ev, "scene")));
		if (case_id)
			printf(", case %s (%lld of %lld)", case_id, json_integer_value(json_object_get(ev, "case_index")) + 1,
			       json_integer_value(json_object_get(ev, "cases")));
		putchar('\n');
	} else if (!strcmp(type, "reference_frame") || !strcmp(type, "method_frame")) {
		if (case_id)
			printf("%lld %s frame %lld %-12s", seq, case_id, json_integer_value(json_object_get(ev, "frame")),
			       json_string_value(json_object_get(ev, "method")));
		else
			printf("%lld frame %lld %-12s", seq, json_integer_value(json_object_get(ev, "frame")),
			       json_string_value(json_object_get(ev, "method")));
		print_number("gpu", json_object_get(ev, "gpu_ms"), " ms");
		json_t *m = json_object_get(ev, "metrics");
		if (m) {
			print_number("psnr", json_object_get(m, "psnr"), " dB");
			print_number("ssim", json_object_get(m, "ssim"), "");
		}
		printf(" [%lld/%lld]\n", json_integer_value(json_object_get(ev, "done")),
		       json_integer_value(json_object_get(ev, "total")));
	} else if (!strcmp(type, "job_failed")) {
		json_t *e = json_object_get(ev, "error");
		printf("%lld failed: %s\n", seq, json_string_value(json_object_get(e, "message")));
	} else {
		printf("%lld %s\n", seq, type);
	}
}

/* The watch's last line, where a person looks when it ends: the job's state, its wall time, where its
 * results are and the verdict ("job 000003 done in 12s; results: aalab get 000003; verdict: front: ..."). */
static void print_final_line(struct aa_conn *c, const char *job)
{
	json_t *msg = json_pack("{ss ss}", "op", "status", "job", job);
	json_t *r = aa_conn_request(c, msg, NULL, NULL);
	json_decref(msg);
	json_t *j = json_object_get(r, "job");
	const char *state = json_string_value(json_object_get(j, "state"));
	if (!state) {
		json_decref(r);
		return;
	}
	json_t *started = json_object_get(j, "started_at"), *finished = json_object_get(j, "finished_at");
	char wall[32] = "";
	if (json_is_number(started) && json_is_number(finished))
		aa_format_duration(json_number_value(finished) - json_number_value(started), wall, sizeof wall);
	printf("job %s %s%s%s", job, state, wall[0] ? " in " : "", wall);
	if (!strcmp(state, "done")) {
		json_t *results = aa_job_results(c, job);
		char headline[1024] = "";
		if (results)
			aa_verdict_headline(results, headline, sizeof headline);
		printf("; results: aalab get %s (results.json, report.html)%s%s", job, headline[0] ? "; verdict: " : "",
		       headline);
		json_decref(results);
	} else if (json_object_get(j, "error")) {
		printf(": %s", json_string_value(json_object_get(json_object_get(j, "error"), "message")));
	}
	putchar('\n');
	fflush(stdout);
	json_decref(r);
}

int aa_watch_job(struct aa_conn *c, const char *cmd, const char *job, long after, enum aa_watch_output output)
{
	json_t *msg = json_pack("{ss ss sI}", "op", "watch", "job", job, "after", (json_int_t)after);
	json_t *r = aa_conn_request(c, msg, NULL, NULL);
	json_decref(msg);
	int status = aa_reply_status(cmd, r);
	json_decref(r);
	if (status)
		return status;
	const bool json = output == AA_WATCH_JSON, quiet = output == AA_WATCH_QUIET;
	const bool tty = isatty(STDERR_FILENO) && !quiet && !json;
	const char *last = "";
	char last_buf[32] = "";
	int last_total = 0;
	for (;;) {
		json_t *ev = aa_conn_read(c, NULL, NULL);
		if (!ev) {
			fprintf(stderr, "aalab %s: the daemon closed the connection during the watch\n", cmd);
			return AA_EXIT_FAILED;
		}
		const char *type = json_string_value(json_object_get(ev, "event"));
		if (!type) {
			json_decref(ev);
			continue;
		}
		if (!strcmp(type, "watch_end")) {
			json_decref(ev);
			break;
		}
		snprintf(last_buf, sizeof last_buf, "%s", type);
		last = last_buf;
		if (json) {
			json_dumpf(ev, stdout, JSON_COMPACT);
			fputc('\n', stdout);
			fflush(stdout);
		} else if (tty || output == AA_WATCH_PROGRESS) {
			json_t *done = json_object_get(ev, "done");
			int d = (int)json_integer_value(done), t = (int)json_integer_value(json_object_get(ev, "total"));
			if (done)
				last_total = t;
			/* the frames' events count the renders so far, re-timings included, but none follows the
			 * last re-timings: the end of the job is all of them */
			if (!done && !strcmp(type, "job_finished") && last_total > 0) {
				done = ev;
				d = t = last_total;
			}
			if (done && tty)
				aa_progress_update(d, t, json_string_value(json_object_get(ev, "method")));
			else if (done)
				aa_progress_line(cmd, d, t, "rendering");
		} else if (!quiet) {
			print_event(ev);
			fflush(stdout);
		}
		if (!strcmp(type, "job_failed") && !json) {
			json_t *e = json_object_get(ev, "error");
			char lead[128];
			snprintf(lead, sizeof lead, "aalab %s: job %s failed: ", cmd, job);
			if (tty)
				aa_progress_finish();
			aa_print_field_error(lead, json_string_value(json_object_get(e, "path")),
					     json_string_value(json_object_get(e, "message")));
		}
		json_decref(ev);
	}
	aa_progress_finish();
	if (output == AA_WATCH_EVENTS)
		print_final_line(c, job);
	if (!strcmp(last, "job_finished"))
		return AA_EXIT_OK;
	if (!strcmp(last, "job_cancelled") && !json)
		fprintf(stderr, "aalab %s: job %s was cancelled\n", cmd, job);
	return AA_EXIT_FAILED;
}

int cmd_watch(int argc, char **argv)
{
	enum { OPT_AFTER = 256, OPT_CONNECT, OPT_JSON, OPT_QUIET, OPT_HELP, OPT_TOKEN_FILE };
	static const struct option opts[] = {
		{"after", required_argument, 0, OPT_AFTER}, {"connect", required_argument, 0, OPT_CONNECT},
		{"json", no_argument, 0, OPT_JSON}, {"quiet", no_argument, 0, OPT_QUIET},
		{"token-file", required_argument, 0, OPT_TOKEN_FILE}, {"help", no_argument, 0, OPT_HELP}, {0, 0, 0, 0},
	};
	const char *connect = NULL;
	long after = 0;
	bool json = false, quiet = false;
	int c;
	optind = 1;
	while ((c = getopt_long(argc, argv, "", opts, NULL)) != -1) {
		char *end;
		switch (c) {
		case OPT_AFTER:
			after = strtol(optarg, &end, 10);
			if (*end || after < 0) {
				fprintf(stderr, "aalab watch: after: expected an event number, got '%s'\n", optarg);
				return AA_EXIT_USAGE;
			}
			break;
		case OPT_CONNECT: connect = optarg; break;
		case OPT_TOKEN_FILE: aa_conn_set_token_file(optarg); break;
		case OPT_JSON: json = true; break;
		case OPT_QUIET: quiet = true; break;
		case OPT_HELP: fputs(aa_watch_help, stdout); return AA_EXIT_OK;
		default: fputs(aa_watch_help, stderr); return AA_EXIT_USAGE;
		}
	}
	if (optind + 1 != argc) {
		fputs(aa_watch_help, stderr);
		return AA_EXIT_USAGE;
	}
	struct aa_conn *conn;
	char err[1200];
	if (aa_conn_open(connect, &conn, err, sizeof err)) {
		fprintf(stderr, "aalab watch: %s\n", err);
		return AA_EXIT_FAILED;
	}
	int status = aa_watch_job(conn, "watch", argv[optind], after,
				  json ? AA_WATCH_JSON : quiet ? AA_WATCH_QUIET : AA_WATCH_EVENTS);
	aa_conn_close(conn);
	return status;
}
