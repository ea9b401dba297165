/* The aalab command-line client: one file per group of subcommands, each an entry in aalab.c's table. */
#ifndef AA_CLIENT_H
#define AA_CLIENT_H

#include <getopt.h>
#include <stdbool.h>
#include <stdio.h>

#include "types/job.h"

struct aa_cmd_entry {
	const char *name;
	const char *summary;
	int (*exec)(int argc, char **argv);
	const char *help;   /* the full --help text: every option with its default */
};

extern const char aa_run_help[], aa_submit_help[], aa_watch_help[], aa_status_help[], aa_list_help[],
	aa_cancel_help[], aa_get_help[];

/* The job options of run, submit and slurm (job_args.c parses them), as their --help lists them. */
#define AA_JOB_OPTIONS_HELP \
	"  --scene NAME|FILE       scene name (see 'aalab scenes') or scene file (default thin-wires)\n" \
	"  --path NAME             camera path: default, static, or one the scene defines (default default)\n" \
	"  --methods LIST          comma-separated methods, e.g. none,fxaa,smaa (default none,ssaa:16;\n" \
	"                          see 'aalab methods'; user:file=FILE.json for your own). Values joined\n" \
	"                          by '|' sweep a parameter, one method per configuration:\n" \
	"                          fxaa:preset=10|20|39, msaa:2|4|8 (at most 24 methods in all)\n" \
	"  --frames N              frames to render (default 1)\n" \
	"  --first-frame N         frame index on the path to start at (default 0)\n" \
	"  --size WxH              image size (default 640x360)\n" \
	"  --reference-samples N   samples of the accumulated reference, even (default 64); auto: doubled per\n" \
	"                          frame until the N/2-vs-N PSNR reaches 45 dB (cap 256)\n" \
	"  --repeat N|auto         render and time each method's frame N times, the first scored (default\n" \
	"                          auto: the fewest repeats that give each method 5 timed renders, 5 for one\n" \
	"                          frame, 1 from five frames on; job field timing.repeat). With fewer than 5\n" \
	"                          timed renders a method's cost is not ranked\n" \
	"  --label KEY=VALUE       name the run for a build farm (commit, branch, build_url, machine);\n" \
	"                          repeatable, stored in results.json (job field labels; default none)\n" \
	"  --over-threshold X      count the pixels where any of R,G,B differs from the reference by more\n" \
	"                          than X of full scale, as idiff does (0..1, default 0.01; job field\n" \
	"                          over_threshold): the table's 'px >1% off' column\n" \
	"  --baseline JOB          aalabd only: compare the finished job with JOB, a job id or\n" \
	"                          latest:KEY=VALUE (job field baseline; default none)\n"

/* The options of every command that talks to aalabd. */
#define AA_CONNECT_OPTIONS_HELP \
	"  --connect ADDRESS       the aalabd to use: unix:PATH or tcp:HOST:PORT (default $AALAB_CONNECT, then\n" \
	"                          $XDG_RUNTIME_DIR/aalabd.sock, then /run/aalabd/aalabd.sock)\n" \
	"  --token-file FILE       on TCP, send the token in FILE's first line (default $AALAB_TOKEN, then\n" \
	"                          the file $AALAB_TOKEN_FILE names)\n"

/* Exit statuses: 0 success, 1 the work failed (or a --fail-above gate tripped), 2 bad usage or input. */
#define AA_EXIT_OK 0
#define AA_EXIT_FAILED 1
#define AA_EXIT_USAGE 2

int cmd_run(int argc, char **argv);
int cmd_scenes(int argc, char **argv);
int cmd_methods(int argc, char **argv);

int cmd_submit(int argc, char **argv);
int cmd_watch(int argc, char **argv);
int cmd_status(int argc, char **argv);
int cmd_jobs(int argc, char **argv);
int cmd_cancel(int argc, char **argv);
int cmd_get(int argc, char **argv);
int cmd_diff(int argc, char **argv);
int cmd_compare(int argc, char **argv);
int cmd_suites(int argc, char **argv);
extern const char aa_compare_help[];
/* suite_table.c: the summary table of a suite's results.json, across cases (method rows per case). */
void aa_print_suite_table(json_t *results, FILE *out);
/* client/verdict_table.c: the verdicts of a suite run with "verdicts": true; returns how many failed that
 * must hold (0 when the results have no verdicts). */
int aa_print_verdict_table(json_t *results, FILE *out);
/* table.c: a results.json document as every command prints it: the verdict first, then the table (a
 * suite's summary, or the methods of a job), then the warnings. */
void aa_print_results(json_t *results, FILE *out);
/* The cost-vs-accuracy table of one job's (or case's) results.json. */
void aa_print_results_table(json_t *results, FILE *out);
/* verdict_lines.c: the verdict ("verdict: HEADLINE" and what beats each other method; for a suite each
 * case's headline), the warnings after a table ("warnings (N):", each with what to do; returns N), and
 * the headline alone. */
void aa_print_verdict(json_t *results, FILE *out);
int aa_print_warnings(json_t *results, FILE *out);
void aa_verdict_headline(json_t *results, char *out, size_t size);
/* The verdict's word for a method of one job's (or case's) document: "front", "beaten by smaa",
 * "not ranked", or "-" without a verdict. */
void aa_verdict_place(json_t *doc, const char *label, char *out, size_t size);
extern const char aa_diff_help[];
/* Shards on a farm (docs/farm.md): aalab merge joins shard folders, aalab slurm writes and submits the
 * Slurm scripts. */
int cmd_merge(int argc, char **argv);
int cmd_slurm(int argc, char **argv);
extern const char aa_merge_help[], aa_slurm_help[];
/* cmd_cache.c: aalab cache (stats, clear, verify of the reference store), and where the store is: the
 * folder given (--reference-cache DIR), none for "off" (out is ""), else $XDG_CACHE_HOME/aalab/references
 * or ~/.cache/aalab/references. -1 after printing why. */
int cmd_cache(int argc, char **argv);
extern const char aa_cache_help[];
int aa_reference_cache_location(const char *given, char *out, size_t size);

/* job_args.c: the job flags of run and submit. The long options, for getopt_long with a longindex;
 * aa_job_flag(cmd, option name, value, job) returns 0 (set), -1 (bad value, printed) or 1 (not a job flag). */
#define AA_OPT_JOB 1000
#define AA_JOB_LONG_OPTIONS \
	{"scene", required_argument, 0, AA_OPT_JOB}, {"path", required_argument, 0, AA_OPT_JOB}, \
	{"methods", required_argument, 0, AA_OPT_JOB}, {"frames", required_argument, 0, AA_OPT_JOB}, \
	{"first-frame", required_argument, 0, AA_OPT_JOB}, {"size", required_argument, 0, AA_OPT_JOB}, \
	{"reference-samples", required_argument, 0, AA_OPT_JOB}, {"repeat", required_argument, 0, AA_OPT_JOB}, \
	{"label", required_argument, 0, AA_OPT_JOB}, {"baseline", required_argument, 0, AA_OPT_JOB}, \
	{"over-threshold", required_argument, 0, AA_OPT_JOB}
int aa_job_flag(const char *cmd, const char *flag, const char *value, json_t *job);
/* A job file, or the suite of that name ("smoke": suites/smoke.json) when no such file exists. */
json_t *aa_job_load_file(const char *cmd, const char *path);
/* The job: argv[first] (a job file or suite name) if given, with the flags' fields over it (--label adds
 * to the file's labels); NULL after printing why. */
json_t *aa_job_build(const char *cmd, int argc, char **argv, int first, json_t *overrides);
/* Prints "aalab CMD: path: message" to stderr, naming the field once: messages that already name it (a
 * scene file's "file: path: what is wrong") are printed as they are. */
void aa_print_error(const char *cmd, const struct aa_error *err);
/* Prints "LEAD path: message" to stderr, or "LEAD message" when the message names the path already (it
 * starts with "path:" or holds ": path:") or there is none: the rule of aa_print_error, also for the
 * daemon's errors (replies, a failed job's event). A NULL message prints "error". */
void aa_print_field_error(const char *lead, const char *path, const char *message);

/* remote.c: a connection to aalabd (docs/protocol.md). address: "unix:PATH", "tcp:HOST:PORT", a socket
 * path, or NULL for $AALAB_CONNECT / $XDG_RUNTIME_DIR/aalabd.sock / /run/aalabd/aalabd.sock. TCP sends
 * the token of --token-file (aa_conn_set_token_file), $AALAB_TOKEN or $AALAB_TOKEN_FILE; a refused one
 * is said to be missing or wrong, with where it came from. */
void aa_conn_set_token_file(const char *path);
struct aa_conn;
int aa_conn_open(const char *address, struct aa_conn **out, char *err, size_t err_size);
void aa_conn_close(struct aa_conn *c);
int aa_conn_send(struct aa_conn *c, json_t *msg, const void *payload, size_t size);
/* The next message; its payload (if it announced one) in *payload (malloc'ed). NULL at end of stream. */
json_t *aa_conn_read(struct aa_conn *c, char **payload, size_t *size);
json_t *aa_conn_request(struct aa_conn *c, json_t *msg, char **payload, size_t *size);
/* Options of the service commands: [JOB] [--connect ADDRESS] [--token-file FILE] [--json] and, where the
 * command's help names them, --state, --out, --file, --no-images, --label, --suite, --no-wait. Returns 0,
 * 1 (help printed) or -1 (usage printed). */
struct aa_service_args {
	const char *connect, *job, *state, *out, *file, *suite;
	bool json, no_images, no_wait;
	int label_count;           /* --label KEY=VALUE filters (aalab list) */
	const char *labels[16];
};
int aa_service_args(const char *cmd, const char *help, int argc, char **argv, struct aa_service_args *a);
/* 0 for an ok reply; otherwise prints "aalab CMD: path: message" and returns the exit status. */
int aa_reply_status(const char *cmd, json_t *reply);
/* cmd_watch.c: what a watch prints of the job's events. EVENTS: a progress bar on a terminal, one plain
 * line per event on stdout otherwise; JSON: the events as JSON lines; PROGRESS (aalab run, whose stdout
 * is for the table): a progress bar on a terminal, a line per tenth on stderr otherwise; QUIET: nothing. */
enum aa_watch_output { AA_WATCH_EVENTS, AA_WATCH_JSON, AA_WATCH_PROGRESS, AA_WATCH_QUIET };
/* Streams a job's events; returns the exit status (0 done, 1 failed or cancelled). */
int aa_watch_job(struct aa_conn *c, const char *cmd, const char *job, long after, enum aa_watch_output output);
/* cmd_get.c: downloads a job's files into dir (all, or results.json and report.html only). */
int aa_get_job_files(struct aa_conn *c, const char *cmd, const char *job, const char *dir, bool images);
/* A finished job's results.json, parsed; NULL when it has none (yet) or the request failed. */
json_t *aa_job_results(struct aa_conn *c, const char *job);
/* cmd_submit.c: `aalab run` through the daemon: submit, watch, download into dir, print. */
/* Runs the job on aalabd and fetches its files into dir; the table names shown_dir (where they end up). */
int aa_run_remote(struct aa_conn *c, json_t *job, const char *dir, const char *shown_dir, bool images,
		  bool print_json, bool quiet);

/* method_files.c: the method and shader files of the job's user methods (docs/user-methods.md), read
 * from disk into a JSON object name -> text (*files NULL when the job has none); with compile, their
 * shaders are compiled here first. -1 after printing why. */
int aa_job_user_files(const char *cmd, const json_t *job, bool compile, json_t **files);
/* The payload of submit: nothing, the scene file alone (format "scene"), or a bundle {"files", "scene"}
 * (format "bundle") when there are user method files. *payload is malloc'ed. */
int aa_submit_payload(json_t *files, const char *scene, size_t scene_size, char **payload, size_t *size,
		      const char **format);

/* cmd_list.c: the usage lines of the listing commands, and their argument check: --json and up to
 * max_names names (*first: the first name's index in argv, 0 when none); otherwise exit status 2. */
#define AA_SCENES_USAGE "scenes [NAME|FILE.json] [--json]"
#define AA_METHODS_USAGE "methods [NAME ...] [--json]"
#define AA_SUITES_USAGE "suites [--json]"
int aa_list_args(const char *cmd, const char *usage, int argc, char **argv, int max_names, bool *json,
		 int *first);

/* progress.c: a progress bar on a terminal (renders done, time so far, an estimate of the time left), a
 * line per tenth elsewhere: "aalab CMD: WHAT D/T (P%, ETA T)" each time the share done passes another
 * tenth, so a long job says where it is in at most ten lines. aa_progress_finish erases the bar. */
void aa_progress_update(int done, int total, const char *what);
void aa_progress_line(const char *cmd, int done, int total, const char *what);
void aa_progress_finish(void);
/* Seconds since the first update (0 before one). */
double aa_progress_seconds(void);
/* "12s", "3m05s", "1h02m". */
void aa_format_duration(double seconds, char *out, size_t size);

/* job_args.c: splits a --methods value into method strings: commas separate methods, except that a "key=value"
 * token without ':' continues the previous method's parameters ("fxaa:preset=12,subpix=0.5,none"). */
int aa_split_methods(const char *text, char ***out, int *count);
void aa_free_strings(char **v, int count);

#endif
