/* aalab slurm: writes a Slurm batch array script (one task per shard of the job) and a merge script that
 * runs after every shard succeeded, and with --submit queues both (docs/farm.md). aalab schedules
 * nothing itself: Slurm does. */
#include <errno.h>
#include <getopt.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "run/engine.h"
#include "client.h"
#include "run/shard.h"
#include "run/job_spec.h"
#include "util/file_io.h"

const char aa_slurm_help[] =
	"usage: aalab slurm [JOB.json|SUITE] [options] --shards N --out DIR\n"
	"\n"
	"Splits the job into N shards of contiguous frames (a suite: of whole cases) and writes, in DIR:\n"
	"  job.json        the job, in canonical form\n"
	"  shards.sbatch   a Slurm array job, one task per shard: aalab run job.json --shard $SLURM_ARRAY_TASK_ID/N\n"
	"                  into DIR/shards/TASK (requeued by Slurm when a node fails)\n"
	"  merge.sbatch    aalab merge of DIR/shards/* into DIR/merged, to run with --dependency=afterok\n"
	"With --submit it runs sbatch for both and prints the Slurm job ids. DIR must be on storage that every\n"
	"node sees (docs/farm.md).\n"
	"\n"
	AA_JOB_OPTIONS_HELP
	"  --shards N              shards (array tasks), 1 to the job's frames (a suite's cases); required\n"
	"  --out DIR               the farm folder (required; created; one that holds a job.json already only\n"
	"                          with --force)\n"
	"  --partition P           #SBATCH --partition of both scripts (default: none, Slurm's default)\n"
	"  --gres G                #SBATCH --gres of the shards, e.g. gpu:1 (default: none)\n"
	"  --time T                #SBATCH --time of both scripts, e.g. 30:00 (default: none, the partition's)\n"
	"  --aalab PATH            the aalab the nodes run (default: this one, by absolute path)\n"
	"  --reference-cache DIR|off  the store of reference frames every shard reads and fills (default: this\n"
	"                          user's, $XDG_CACHE_HOME/aalab/references or ~/.cache/aalab/references): it\n"
	"                          must be on storage every node sees, so that no shard renders a reference\n"
	"                          another one, or an earlier job, rendered\n"
	"  --submit                run sbatch and print the job ids\n"
	"  --force                 write the scripts into an earlier farm folder (its shards stay; each task\n"
	"                          replaces its own, and merge checks that every shard is of this job)\n"
	"\n"
	"Exit status: 0 written (and submitted), 1 sbatch failed, 2 bad arguments or job.\n";

/* Values that go into #SBATCH lines and shell words: no spaces, quotes or shell syntax. */
static int check_word(const char *flag, const char *v)
{
	if (!*v || strspn(v, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_.:,=+-/@%") != strlen(v)) {
		fprintf(stderr, "aalab slurm: --%s: \"%s\" has characters Slurm scripts cannot carry safely; use "
			"letters, digits and _ . : , = + - / @ %%\n", flag, v);
		return -1;
	}
	return 0;
}

static int write_text(const char *path, const char *text, mode_t mode)
{
	FILE *f = fopen(path, "w");
	if (!f || fputs(text, f) < 0 || fclose(f) != 0) {
		fprintf(stderr, "aalab slurm: cannot write %s: %s\n", path, strerror(errno));
		return -1;
	}
	chmod(path, mode);
	return 0;
}

/* sbatch --parsable ARGS...: the job id it prints ("123" or "123;cluster"), or -1. */
static long sbatch(const char *const *args)
{
	int fd[2];
	if (pipe(fd) < 0)
		return -1;
	pid_t pid = fork();
	if (pid == 0) {
		dup2(fd[1], STDOUT_FILENO);
		close(fd[0]);
		close(fd[1]);
		execvp("sbatch", (char *const *)args);
		fprintf(stderr, "aalab slurm: cannot run sbatch: %s\n", strerror(errno));
		_exit(127);
	}
	close(fd[1]);
	char out[256] = "";
	size_t n = 0;
	ssize_t r;
	while (pid > 0 && n + 1 < sizeof out && (r = read(fd[0], out + n, sizeof out - 1 - n)) > 0)
		n += (size_t)r;
	out[n] = '\0';
	close(fd[0]);
	int status = 0;
	if (pid < 0 || waitpid(pid, &status, 0) < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
		return -1;
	char *end;
	long id = strtol(out, &end, 10);
	return end != out && id > 0 ? id : -1;
}

struct slurm_options {
	const char *dir, *aalab, *partition, *gres, *time;
	char references[PATH_MAX];  /* the store of references every shard reads and fills, or "off" */
	int shards;
	char hash[80];
	char what[64];             /* "24 frames, warm-up 32" or "6 cases" */
};

static void common_lines(FILE *o, const struct slurm_options *so)
{
	if (so->partition)
		fprintf(o, "#SBATCH --partition=%s\n", so->partition);
	if (so->time)
		fprintf(o, "#SBATCH --time=%s\n", so->time);
}

static char *shards_script(const struct slurm_options *so)
{
	char *text = NULL;
	size_t size = 0;
	FILE *o = open_memstream(&text, &size);
	if (!o)
		return NULL;
	fprintf(o, "#!/bin/sh\n"
		"# Written by 'aalab slurm': %d shards of job %s (%s).\n"
		"# Task I renders shard I of the job into shards/I; merge.sbatch joins them.\n"
		"# Re-run one shard: sbatch --array=I %s/shards.sbatch\n",
		so->shards, so->hash, so->what, so->dir);
	fprintf(o, "#SBATCH --job-name=aalab-shards\n#SBATCH --array=0-%d\n#SBATCH --ntasks=1\n#SBATCH --requeue\n"
		"#SBATCH --output=%s/logs/shard-%%a.log\n", so->shards - 1, so->dir);
	common_lines(o, so);
	if (so->gres)
		fprintf(o, "#SBATCH --gres=%s\n", so->gres);
	/* without --quiet: the shard's log (logs/shard-I.log) shows its progress, a line per tenth */
	fprintf(o, "set -eu\n"
		"exec '%s' run '%s/job.json' --shard \"$SLURM_ARRAY_TASK_ID/%d\" --out \"%s/shards/$SLURM_ARRAY_TASK_ID\" \\\n"
		"\t--force --local --reference-cache '%s'\n", so->aalab, so->dir, so->shards, so->dir, so->references);
	fclose(o);
	return text;
}

static char *merge_script(const struct slurm_options *so)
{
	char *text = NULL;
	size_t size = 0;
	FILE *o = open_memstream(&text, &size);
	if (!o)
		return NULL;
	fprintf(o, "#!/bin/sh\n"
		"# Written by 'aalab slurm': joins the %d shards of job %s into merged/.\n"
		"# Submitted with --dependency=afterok:SHARDS_JOB_ID; a shard that failed is named by aalab merge.\n",
		so->shards, so->hash);
	fprintf(o, "#SBATCH --job-name=aalab-merge\n#SBATCH --ntasks=1\n#SBATCH --kill-on-invalid-dep=yes\n"
		"#SBATCH --output=%s/logs/merge.log\n", so->dir);
	common_lines(o, so);
	fprintf(o, "set -eu\n"
		"set --\n"
		"i=0\n"
		"while [ \"$i\" -lt %d ]; do\n"
		"\tset -- \"$@\" \"%s/shards/$i\"\n"
		"\ti=$((i + 1))\n"
		"done\n"
		"exec '%s' merge --out '%s/merged' --force \"$@\"\n", so->shards, so->dir, so->aalab, so->dir);
	fclose(o);
	return text;
}

int cmd_slurm(int argc, char **argv)
{
	enum { OPT_SHARDS = 256, OPT_OUT, OPT_PARTITION, OPT_GRES, OPT_TIME, OPT_AALAB, OPT_SUBMIT, OPT_FORCE,
	       OPT_HELP, OPT_REFERENCE_CACHE };
	static const struct option opts[] = {
		AA_JOB_LONG_OPTIONS, {"shards", required_argument, 0, OPT_SHARDS}, {"out", required_argument, 0, OPT_OUT},
		{"partition", required_argument, 0, OPT_PARTITION}, {"gres", required_argument, 0, OPT_GRES},
		{"time", required_argument, 0, OPT_TIME}, {"aalab", required_argument, 0, OPT_AALAB},
		{"submit", no_argument, 0, OPT_SUBMIT}, {"force", no_argument, 0, OPT_FORCE},
		{"help", no_argument, 0, OPT_HELP}, {"reference-cache", required_argument, 0, OPT_REFERENCE_CACHE},
		{0, 0, 0, 0},
	};
	struct slurm_options so = {0};
	const char *out = NULL, *shards_text = NULL, *references = NULL;
	bool submit = false, force = false;
	json_t *overrides = json_object(), *job = NULL;
	int status = AA_EXIT_USAGE, c, idx;
	optind = 1;
	while ((c = getopt_long(argc, argv, "", opts, &idx)) != -1) {
		switch (c) {
		case AA_OPT_JOB:
			if (aa_job_flag("slurm", opts[idx].name, optarg, overrides))
				goto done;
			break;
		case OPT_SHARDS: shards_text = optarg; break;
		case OPT_OUT: out = optarg; break;
		case OPT_PARTITION: so.partition = optarg; break;
		case OPT_GRES: so.gres = optarg; break;
		case OPT_TIME: so.time = optarg; break;
		case OPT_AALAB: so.aalab = optarg; break;
		case OPT_SUBMIT: submit = true; break;
		case OPT_FORCE: force = true; break;
		case OPT_REFERENCE_CACHE: references = optarg; break;
		case OPT_HELP: fputs(aa_slurm_help, stdout); status = AA_EXIT_OK; goto done;
		default: fputs(aa_slurm_help, stderr); goto done;
		}
	}
	if (!shards_text || !out) {
		fprintf(stderr, "aalab slurm: %s is required\n", !shards_text ? "--shards N" : "--out DIR");
		goto done;
	}
	char *end;
	long n = strtol(shards_text, &end, 10);
	if (*end || end == shards_text || n < 1 || n > AA_MAX_SHARDS) {
		fprintf(stderr, "aalab slurm: --shards: \"%s\" is not a number of shards; valid range: 1 to %d\n",
			shards_text, AA_MAX_SHARDS);
		goto done;
	}
	so.shards = (int)n;
	if ((so.partition && check_word("partition", so.partition)) || (so.gres && check_word("gres", so.gres)) ||
	    (so.time && check_word("time", so.time)) || check_word("out", out) ||
	    (so.aalab && check_word("aalab", so.aalab)))
		goto done;
	job = aa_job_build("slurm", argc, argv, optind, overrides);
	if (!job)
		goto done;
	struct aa_job_spec spec, shard;
	struct aa_error err = {0};
	if (aa_job_spec_from_json(job, &spec, &err) || aa_shard_job(&spec, so.shards - 1, so.shards, &shard, &err)) {
		fprintf(stderr, "aalab slurm: %s%s%s\n", err.path[0] ? (strcmp(err.path, "shard") ? err.path : "--shards") : "",
			err.path[0] ? ": " : "", err.message);
		goto done;
	}
	/* the tasks run job.json from the farm folder, on other nodes: scene files by absolute path */
	for (int i = 0; i < (spec.is_suite ? spec.case_count : 1); i++) {
		char *scene = spec.is_suite ? spec.cases[i].scene : spec.scene;
		size_t size = spec.is_suite ? sizeof spec.cases[i].scene : sizeof spec.scene, len = strlen(scene);
		char abs_path[PATH_MAX];
		errno = 0;
		if (scene[0] == '/' || (!strchr(scene, '/') && (len < 5 || strcmp(scene + len - 5, ".json") != 0)))
			continue; /* absolute already, or a scene name */
		if (!realpath(scene, abs_path) || strlen(abs_path) >= size) {
			char field[48] = "scene";
			if (spec.is_suite)
				snprintf(field, sizeof field, "cases[%d].scene", i);
			fprintf(stderr, "aalab slurm: %s: cannot use the scene file '%s': %s\n", field, scene,
				errno ? strerror(errno) : "its absolute path is too long");
			goto done;
		}
		snprintf(scene, size, "%s", abs_path);
	}
	if (spec.is_suite)
		snprintf(so.what, sizeof so.what, "%d cases", spec.case_count);
	else
		snprintf(so.what, sizeof so.what, "%d frames, warm-up %d", spec.frames, aa_job_shard_warmup(&spec));
	aa_job_hash(&spec, so.hash, sizeof so.hash);

	/* the folder, by absolute path: the scripts run on other nodes, from other folders */
	if (mkdir(out, 0755) < 0 && errno != EEXIST) {
		fprintf(stderr, "aalab slurm: --out: cannot create %s: %s\n", out, strerror(errno));
		status = AA_EXIT_FAILED;
		goto done;
	}
	char dir[PATH_MAX], self[PATH_MAX], path[PATH_MAX + 64];
	if (!realpath(out, dir)) {
		fprintf(stderr, "aalab slurm: --out: %s: %s\n", out, strerror(errno));
		goto done;
	}
	so.dir = dir;
	/* one store for every shard, by absolute path (made here, so that the path is known to exist) */
	char store[PATH_MAX];
	if (aa_reference_cache_location(references, store, sizeof store))
		goto done;
	snprintf(so.references, sizeof so.references, "off");
	if (store[0]) {
		struct aa_error serr = {0};
		if (aa_file_make_dirs(store, &serr) || !realpath(store, so.references)) {
			fprintf(stderr, "aalab slurm: --reference-cache: %s\n", serr.message[0] ? serr.message : strerror(errno));
			goto done;
		}
		if (check_word("reference-cache", so.references))
			goto done;
	}
	if (!force) {
		snprintf(path, sizeof path, "%s/job.json", dir);
		if (access(path, F_OK) == 0) {
			fprintf(stderr, "aalab slurm: --out: %s already holds a farm folder; give --force to replace its "
				"scripts (the shards already there are kept and --force'd by each task)\n", dir);
			goto done;
		}
	}
	if (!so.aalab) {
		ssize_t len = readlink("/proc/self/exe", self, sizeof self - 1);
		if (len <= 0) {
			fprintf(stderr, "aalab slurm: cannot find this aalab's path; give --aalab PATH\n");
			status = AA_EXIT_FAILED;
			goto done;
		}
		self[len] = '\0';
		so.aalab = self;
		if (check_word("aalab", so.aalab))
			goto done;
	}
	if (check_word("out", dir))
		goto done;
	json_t *cj = aa_job_spec_to_json(&spec);
	char *job_text = cj ? json_dumps(cj, JSON_INDENT(2)) : NULL;
	json_decref(cj);
	char *shards = shards_script(&so), *merge = merge_script(&so);
	snprintf(path, sizeof path, "%s/logs", dir);
	int failed = !job_text || !shards || !merge || (mkdir(path, 0755) < 0 && errno != EEXIST);
	if (!failed) {
		size_t len = strlen(job_text);
		char *with_newline = realloc(job_text, len + 2);
		if (with_newline) {
			job_text = with_newline;
			strcpy(job_text + len, "\n");
		}
		snprintf(path, sizeof path, "%s/job.json", dir);
		failed = write_text(path, job_text, 0644);
		snprintf(path, sizeof path, "%s/shards.sbatch", dir);
		failed = failed || write_text(path, shards, 0755);
		snprintf(path, sizeof path, "%s/merge.sbatch", dir);
		failed = failed || write_text(path, merge, 0755);
	}
	free(job_text);
	free(shards);
	free(merge);
	if (failed) {
		status = AA_EXIT_FAILED;
		goto done;
	}
	printf("job %s (%s) in %d shards\nwrote %s/shards.sbatch and %s/merge.sbatch\n", so.hash, so.what, so.shards,
	       dir, dir);
	if (!submit) {
		printf("submit with:\n  id=$(sbatch --parsable %s/shards.sbatch)\n"
		       "  sbatch --dependency=afterok:$id %s/merge.sbatch\n", dir, dir);
		status = AA_EXIT_OK;
		goto done;
	}
	char shards_path[PATH_MAX + 32], merge_path[PATH_MAX + 32], dep[64];
	snprintf(shards_path, sizeof shards_path, "%s/shards.sbatch", dir);
	snprintf(merge_path, sizeof merge_path, "%s/merge.sbatch", dir);
	const char *first_args[] = {"sbatch", "--parsable", shards_path, NULL};
	long shards_id = sbatch(first_args);
	if (shards_id < 0) {
		fprintf(stderr, "aalab slurm: sbatch %s failed\n", shards_path);
		status = AA_EXIT_FAILED;
		goto done;
	}
	snprintf(dep, sizeof dep, "--dependency=afterok:%ld", shards_id);
	const char *merge_args[] = {"sbatch", "--parsable", dep, merge_path, NULL};
	long merge_id = sbatch(merge_args);
	printf("shards: Slurm job %ld (array 0-%d)\n", shards_id, so.shards - 1);
	if (merge_id < 0) {
		fprintf(stderr, "aalab slurm: sbatch %s failed; the shards are queued: run it after them with\n"
			"  sbatch --dependency=afterok:%ld %s\n", merge_path, shards_id, merge_path);
		status = AA_EXIT_FAILED;
		goto done;
	}
	printf("merge:  Slurm job %ld (after every shard succeeded)\nresults: %s/merged\n", merge_id, dir);
	fflush(stdout);
	status = AA_EXIT_OK;
done:
	json_decref(job);
	json_decref(overrides);
	return status;
}
