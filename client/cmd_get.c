/* aalab get: downloads a job's stored results from aalabd (results.json, report.html, frames), or prints
 * one of its files. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "client.h"

const char aa_get_help[] =
	"usage: aalab get JOB [options]\n"
	"\n"
	"Downloads a finished job's results.json, report.html and frame images from aalabd.\n"
	"\n"
	"  --out DIR               where they go (default results/job-JOB)\n"
	"  --file NAME             write only this file to standard output: results.json, report.html,\n"
	"                          frames/METHOD/NNNN.png, ... (default: every file, into DIR)\n"
	"  --no-images             only results.json and report.html, no frame images\n"
	"  --json                  print results.json to standard output instead\n"
	AA_CONNECT_OPTIONS_HELP
	"\n"
	"Exit status: 0 downloaded, 1 the daemon could not be reached or a file not written, 2 unknown job.\n";

static json_t *request_file(struct aa_conn *c, const char *job, const char *file, char **data, size_t *size)
{
	json_t *msg = json_pack("{ss ss}", "op", "get", "job", job);
	if (file)
		json_object_set_new(msg, "file", json_string(file));
	json_t *r = aa_conn_request(c, msg, data, size);
	json_decref(msg);
	return r;
}

static int mkdir_parents(char *path)
{
	for (char *p = path + 1; *p; p++)
		if (*p == '/') {
			*p = 0;
			int rc = mkdir(path, 0777);
			*p = '/';
			if (rc && errno != EEXIST)
				return -1;
		}
	return 0;
}

int aa_get_job_files(struct aa_conn *c, const char *cmd, const char *job, const char *dir, bool images)
{
	json_t *r = request_file(c, job, NULL, NULL, NULL);
	int status = aa_reply_status(cmd, r);
	if (status) {
		json_decref(r);
		return status;
	}
	size_t i;
	json_t *f;
	json_array_foreach(json_object_get(r, "files"), i, f) {
		const char *name = json_string_value(f);
		/* a suite's case folders hold images as a job's folder does */
		const char *inner = name && !strncmp(name, "cases/", 6) && strchr(name + 6, '/') ? strchr(name + 6, '/') + 1 : name;
		bool image = inner && (!strncmp(inner, "frames/", 7) || !strncmp(inner, "diff/", 5) || !strncmp(inner, "flip/", 5) ||
				      !strncmp(inner, "viewer/", 7) || !strncmp(inner, "exr/", 4));
		if (!name || (image && !images) || strstr(name, "..") || name[0] == '/')
			continue;
		char *data;
		size_t size;
		json_t *fr = request_file(c, job, name, &data, &size);
		status = aa_reply_status(cmd, fr);
		json_decref(fr);
		if (status)
			break;
		char path[2048];
		snprintf(path, sizeof path, "%s/%s", dir, name);
		FILE *out = mkdir_parents(path) == 0 ? fopen(path, "wb") : NULL;
		if (!out || fwrite(data, 1, size, out) != size) {
			fprintf(stderr, "aalab %s: cannot write %s: %s\n", cmd, path, strerror(errno));
			status = AA_EXIT_FAILED;
		}
		if (out && fclose(out))
			status = AA_EXIT_FAILED;
		free(data);
		if (status)
			break;
	}
	json_decref(r);
	return status;
}

json_t *aa_job_results(struct aa_conn *c, const char *job)
{
	char *data = NULL;
	size_t size = 0;
	json_t *r = request_file(c, job, "results.json", &data, &size);
	json_t *doc = json_is_true(json_object_get(r, "ok")) && data ? json_loadb(data, size, 0, NULL) : NULL;
	json_decref(r);
	free(data);
	return doc;
}

int cmd_get(int argc, char **argv)
{
	struct aa_service_args a;
	int rc = aa_service_args("get", aa_get_help, argc, argv, &a);
	if (rc)
		return rc > 0 ? AA_EXIT_OK : AA_EXIT_USAGE;
	if (!a.job) {
		fputs(aa_get_help, stderr);
		return AA_EXIT_USAGE;
	}
	struct aa_conn *conn;
	char err[1200];
	if (aa_conn_open(a.connect, &conn, err, sizeof err)) {
		fprintf(stderr, "aalab get: %s\n", err);
		return AA_EXIT_FAILED;
	}
	int status;
	if (a.file || a.json) {
		char *data = NULL;
		size_t size = 0;
		json_t *r = request_file(conn, a.job, a.file ? a.file : "results.json", &data, &size);
		status = aa_reply_status("get", r);
		if (status == AA_EXIT_OK && fwrite(data, 1, size, stdout) != size)
			status = AA_EXIT_FAILED;
		free(data);
		json_decref(r);
	} else {
		char dir[1100];
		snprintf(dir, sizeof dir, "%s", a.out ? a.out : "");
		if (!a.out)
			snprintf(dir, sizeof dir, "results/job-%.64s", a.job);
		status = aa_get_job_files(conn, "get", a.job, dir, !a.no_images);
		if (status == AA_EXIT_OK)
			printf("%s/results.json\n%s/report.html\n", dir, dir);
	}
	aa_conn_close(conn);
	return status;
}
