/* aalab submit: sends a job (a job file and/or the run flags) to aalabd and prints its id; with --watch
 * it then streams the job's progress. Also `aalab run` through a running daemon. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "client.h"
#include "util/file_open.h"

const char aa_submit_help[] =
	"usage: aalab submit [JOB.json|SUITE] [options]\n"
	"\n"
	"Queues a job on aalabd and prints its id. A scene given as a file (--scene ./my.json, or a job\n"
	"file's scene) is sent with the job, as --scene-file sends one; the daemon knows scenes by name.\n"
	"\n"
	AA_JOB_OPTIONS_HELP
	"  --scene-file FILE       send this scene file with the job (default: none; the job's --scene when\n"
	"                          that is a file)\n"
	"  --watch                 follow the job until it ends, as aalab watch does after the id: a progress\n"
	"                          bar on a terminal, one line per event otherwise, then a last line with the\n"
	"                          state, wall time, where the results are and the verdict; the exit status\n"
	"                          is then the job's (0 done, 1 failed or cancelled)\n"
	"  --json                  print the reply (and with --watch the events) as JSON lines\n"
	"  --quiet                 with --watch, print nothing but the id\n"
	AA_CONNECT_OPTIONS_HELP
	"\n"
	"Exit status: 0 queued (with --watch: done), 1 the daemon could not be reached (with --watch: the job\n"
	"failed or was cancelled), 2 bad arguments or job.\n";

/* Submits and returns the reply (NULL if the connection failed, or the payload could not be made). With
 * user methods in the job, their files go with it (and are compiled here first). */
static json_t *submit(struct aa_conn *c, const char *cmd, json_t *job, const char *scene, size_t scene_size,
		      int *status)
{
	json_t *files;
	char *payload;
	size_t size;
	const char *format;
	*status = AA_EXIT_FAILED;
	if (aa_job_user_files(cmd, job, true, &files)) {
		*status = AA_EXIT_USAGE;
		return NULL;
	}
	int rc = aa_submit_payload(files, scene, scene_size, &payload, &size, &format);
	json_decref(files);
	if (rc) {
		*status = AA_EXIT_USAGE;
		return NULL;
	}
	json_t *msg = json_pack("{ss sO}", "op", "submit", "job", job);
	if (format)
		json_object_set_new(msg, "payload_format", json_string(format));
	rc = aa_conn_send(c, msg, payload, size);
	json_decref(msg);
	free(payload);
	return rc ? NULL : aa_conn_read(c, NULL, NULL);
}

static char *read_file(const char *path, size_t *size, struct aa_error *err)
{
	FILE *f = aa_file_fopen_regular(path, "", err); /* never blocks on a FIFO */
	if (!f)
		return NULL;
	struct stat st;
	char *data = NULL;
	if (fstat(fileno(f), &st) == 0 && st.st_size < (1 << 24) && (data = malloc((size_t)st.st_size + 1)) &&
	    fread(data, 1, (size_t)st.st_size, f) != (size_t)st.st_size) {
		free(data);
		data = NULL;
	}
	*size = data ? (size_t)st.st_size : 0;
	fclose(f);
	return data;
}

int cmd_submit(int argc, char **argv)
{
	enum { OPT_SCENE_FILE = 256, OPT_WATCH, OPT_CONNECT, OPT_JSON, OPT_QUIET, OPT_HELP, OPT_TOKEN_FILE };
	static const struct option opts[] = {
		AA_JOB_LONG_OPTIONS, {"scene-file", required_argument, 0, OPT_SCENE_FILE},
		{"watch", no_argument, 0, OPT_WATCH}, {"connect", required_argument, 0, OPT_CONNECT},
		{"json", no_argument, 0, OPT_JSON}, {"quiet", no_argument, 0, OPT_QUIET},
		{"token-file", required_argument, 0, OPT_TOKEN_FILE}, {"help", no_argument, 0, OPT_HELP}, {0, 0, 0, 0},
	};
	json_t *overrides = json_object();
	const char *connect = NULL, *scene_file = NULL;
	bool watch = false, json = false, quiet = false;
	int c, idx, status = AA_EXIT_USAGE;
	char *scene = NULL;
	size_t scene_size = 0;
	optind = 1;
	while ((c = getopt_long(argc, argv, "", opts, &idx)) != -1) {
		switch (c) {
		case AA_OPT_JOB:
			if (aa_job_flag("submit", opts[idx].name, optarg, overrides))
				goto out;
			break;
		case OPT_SCENE_FILE: scene_file = optarg; break;
		case OPT_WATCH: watch = true; break;
		case OPT_CONNECT: connect = optarg; break;
		case OPT_TOKEN_FILE: aa_conn_set_token_file(optarg); break;
		case OPT_JSON: json = true; break;
		case OPT_QUIET: quiet = true; break;
		case OPT_HELP: fputs(aa_submit_help, stdout); status = AA_EXIT_OK; goto out;
		default: fputs(aa_submit_help, stderr); goto out;
		}
	}
	json_t *job = aa_job_build("submit", argc, argv, optind, overrides);
	if (!job)
		goto out;
	/* a scene given as a file (--scene ./my.json, or a job file's "scene") goes with the job, as
	 * --scene-file sends it: the daemon takes scene names only */
	const char *job_scene = json_string_value(json_object_get(job, "scene"));
	if (!scene_file && job_scene && (strchr(job_scene, '/') || strstr(job_scene, ".json")))
		scene_file = job_scene;
	struct aa_error ferr = {0};
	if (scene_file && !(scene = read_file(scene_file, &scene_size, &ferr))) {
		if (ferr.code == AA_ERR_INVALID) /* a FIFO, socket or device */
			fprintf(stderr, "aalab submit: %s: %s\n", scene_file == job_scene ? "scene" : "scene-file",
				ferr.message);
		else
			fprintf(stderr, "aalab submit: %s: cannot read %s (at most 16 MB)\n",
				scene_file == job_scene ? "scene" : "scene-file", scene_file);
		json_decref(job);
		goto out;
	}
	struct aa_conn *conn;
	char err[1200];
	if (aa_conn_open(connect, &conn, err, sizeof err)) {
		fprintf(stderr, "aalab submit: %s\n", err);
		json_decref(job);
		status = AA_EXIT_FAILED;
		goto out;
	}
	int failed;
	json_t *r = submit(conn, "submit", job, scene, scene_size, &failed);
	json_decref(job);
	status = r || failed != AA_EXIT_USAGE ? aa_reply_status("submit", r) : failed;
	if (status == AA_EXIT_OK) {
		const char *id = json_string_value(json_object_get(r, "job"));
		if (json) {
			json_dumpf(r, stdout, JSON_COMPACT);
			fputc('\n', stdout);
		} else {
			printf("%s\n", id);
		}
		fflush(stdout);
		if (watch)
			status = aa_watch_job(conn, "submit", id, 0,
					      json ? AA_WATCH_JSON : quiet ? AA_WATCH_QUIET : AA_WATCH_EVENTS);
	}
	json_decref(r);
	aa_conn_close(conn);
out:
	free(scene);
	json_decref(overrides);
	return status;
}

int aa_run_remote(struct aa_conn *c, json_t *job, const char *dir, const char *shown_dir, bool images,
		  bool print_json, bool quiet)
{
	if (!images)
		json_object_set_new(job, "keep_frames", json_false());
	int failed;
	json_t *r = submit(c, "run", job, NULL, 0, &failed);
	int status = r || failed != AA_EXIT_USAGE ? aa_reply_status("run", r) : failed;
	if (status) {
		json_decref(r);
		return status;
	}
	char id[32];
	snprintf(id, sizeof id, "%s", json_string_value(json_object_get(r, "job")));
	json_decref(r);
	/* always said, so that a log shows where the numbers came from */
	fprintf(stderr, "aalab run: job %s on aalabd (--local runs in this process)\n", id);
	status = aa_watch_job(c, "run", id, 0, quiet ? AA_WATCH_QUIET : AA_WATCH_PROGRESS); /* stdout is for the table */
	if (status == AA_EXIT_OK)
		status = aa_get_job_files(c, "run", id, dir, images);
	if (status)
		return status;
	char path[1200];
	snprintf(path, sizeof path, "%s/results.json", dir);
	json_t *results = json_load_file(path, 0, NULL);
	if (!results) {
		fprintf(stderr, "aalab run: cannot read %s\n", path);
		return AA_EXIT_FAILED;
	}
	if (print_json) {
		json_dumpf(results, stdout, JSON_INDENT(2));
		fputc('\n', stdout);
	} else {
		aa_print_results(results, stdout);
		aa_print_verdict_table(results, stdout);
		printf("\nresults: %s/results.json\nreport:  %s/report.html\n", shown_dir, shown_dir);
	}
	json_decref(results);
	return AA_EXIT_OK;
}
