/* aalab compare: compares two runs (results folders, results.json files or aalabd job ids), per case and
 * method, and exits 1 when a gate trips; prints a table, JSON, JUnit XML or a markdown summary. */
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "client.h"
#include "compare/compare.h"

const char aa_compare_help[] =
	"usage: aalab compare BASE NEW [options]\n"
	"\n"
	"Compares two runs of the same job or suite, case by case and method by method: each run's verdict\n"
	"(the cost-quality front), then PSNR, SSIM, FLIP, flicker and memory BASE -> NEW with their change,\n"
	"then the GPU time's median BASE -> NEW with its raw change and, apart, the change the gates judge\n"
	"(the p10 over the case's machine factor, with its 90% interval) and each gate's verdict. BASE and NEW\n"
	"are results folders, results.json files or aalabd job ids. Methods pair by label; a label found in\n"
	"one run only pairs with the one method of the same name in the other, and the change of parameters\n"
	"is shown.\n"
	"\n"
	"  --fail-if GATE          a gate, METRIC OP CHANGE[%]: 'psnr < -0.1', 'gpu_ms > +50%', 'flip > +0.005'.\n"
	"                          Metrics: psnr, ssim, flip, flicker, gpu_ms, cpu_ms, memory. Repeatable;\n"
	"                          replaces the default set (psnr < -0.1, ssim < -0.001, flip > +0.005,\n"
	"                          flicker > +0.1, gpu_ms > +50%, memory > +10%), which 'default' names. A time\n"
	"                          (gpu_ms, cpu_ms) counts only when the 90% bootstrap interval of its judged\n"
	"                          change is entirely past the gate\n"
	"  --json                  print the comparison as JSON instead of the table\n"
	"  --junit FILE            also write JUnit XML: one test case per case x method x gate (default: none)\n"
	"  --markdown FILE         also write a markdown summary, for a merge-request comment (default: none)\n"
	"  --allow-missing         compare the cases both runs have (default: runs must have the same cases)\n"
	"  --raw-cost              judge times as measured: no machine factor (for a machine that runs nothing\n"
	"                          else; then a slowdown shared by every method of a case counts too)\n"
	AA_CONNECT_OPTIONS_HELP
	"                          (to fetch runs given as job ids)\n"
	"\n"
	"Exit status: 0 every gate held, 1 a gate tripped, 2 bad input: an unreadable run, a bad gate, runs\n"
	"that do not share their cases, or runs where nothing was judged (no method pairs, or no gate could\n"
	"judge any), named. docs/compare.md has the rules.\n";

/* A run: DIR/results.json, a results.json file, or a job's results.json fetched from aalabd. */
static json_t *load_run(const char *side, const char *source, const char *connect)
{
	char path[4200];
	struct stat st;
	json_error_t jerr;
	if (stat(source, &st) == 0) {
		snprintf(path, sizeof path, S_ISDIR(st.st_mode) ? "%s/results.json" : "%s", source);
		json_t *doc = json_load_file(path, JSON_REJECT_DUPLICATES, &jerr);
		if (!doc)
			fprintf(stderr, "aalab compare: %s: %s:%d:%d: %s\n", side, path, jerr.line, jerr.column, jerr.text);
		return doc;
	}
	size_t digits = strspn(source, "0123456789");
	if (digits == 0 || source[digits] || digits >= 16) {
		fprintf(stderr, "aalab compare: %s: '%s' is neither a results folder, a results.json file nor a job id\n",
			side, source);
		return NULL;
	}
	struct aa_conn *conn;
	char err[1200];
	if (aa_conn_open(connect, &conn, err, sizeof err)) {
		fprintf(stderr, "aalab compare: %s: '%s' is no file here, and as a job id: %s\n", side, source, err);
		return NULL;
	}
	json_t *msg = json_pack("{ss ss ss}", "op", "get", "job", source, "file", "results.json");
	char *data = NULL;
	size_t size = 0;
	json_t *reply = aa_conn_request(conn, msg, &data, &size);
	json_decref(msg);
	json_t *doc = NULL;
	char cmd[64];
	snprintf(cmd, sizeof cmd, "compare: %s", side);
	if (aa_reply_status(cmd, reply) == AA_EXIT_OK) {
		doc = json_loadb(data ? data : "", size, JSON_REJECT_DUPLICATES, &jerr);
		if (!doc)
			fprintf(stderr, "aalab compare: %s: job %s's results.json: %s\n", side, source, jerr.text);
	}
	free(data);
	json_decref(reply);
	aa_conn_close(conn);
	return doc;
}

static int write_output(const char *what, const char *file, const json_t *cmp,
			int (*writer)(const json_t *, FILE *))
{
	FILE *f = fopen(file, "w");
	int rc = f ? writer(cmp, f) : -1;
	if (f && fclose(f) != 0)
		rc = -1;
	if (rc) {
		fprintf(stderr, "aalab compare: %s: cannot write %s\n", what, file);
		return -1;
	}
	return 0;
}

int cmd_compare(int argc, char **argv)
{
	enum { OPT_FAIL_IF = 256, OPT_JSON, OPT_JUNIT, OPT_MARKDOWN, OPT_ALLOW_MISSING, OPT_RAW_COST, OPT_CONNECT, OPT_HELP,
	       OPT_TOKEN_FILE };
	static const struct option opts[] = {
		{"fail-if", required_argument, 0, OPT_FAIL_IF}, {"json", no_argument, 0, OPT_JSON},
		{"junit", required_argument, 0, OPT_JUNIT}, {"markdown", required_argument, 0, OPT_MARKDOWN},
		{"allow-missing", no_argument, 0, OPT_ALLOW_MISSING}, {"raw-cost", no_argument, 0, OPT_RAW_COST},
		{"connect", required_argument, 0, OPT_CONNECT}, {"token-file", required_argument, 0, OPT_TOKEN_FILE},
		{"help", no_argument, 0, OPT_HELP}, {0, 0, 0, 0},
	};
	struct aa_compare_options o = {0};
	const char *junit = NULL, *markdown = NULL, *connect = NULL;
	bool print_json = false;
	struct aa_error err = {0};
	int c;
	optind = 1;
	while ((c = getopt_long(argc, argv, "", opts, NULL)) != -1) {
		switch (c) {
		case OPT_FAIL_IF:
			if (!strcmp(optarg, "default")) {
				o.gate_count += aa_gates_default(o.gates + o.gate_count, AA_MAX_GATES - o.gate_count);
				break;
			}
			if (o.gate_count >= AA_MAX_GATES) {
				fprintf(stderr, "aalab compare: --fail-if: more than %d gates\n", AA_MAX_GATES);
				return AA_EXIT_USAGE;
			}
			if (aa_gate_parse(optarg, &o.gates[o.gate_count], "--fail-if", &err)) {
				fprintf(stderr, "aalab compare: %s: %s\n", err.path, err.message);
				return AA_EXIT_USAGE;
			}
			o.gate_count++;
			break;
		case OPT_JSON: print_json = true; break;
		case OPT_JUNIT: junit = optarg; break;
		case OPT_MARKDOWN: markdown = optarg; break;
		case OPT_ALLOW_MISSING: o.allow_missing = true; break;
		case OPT_RAW_COST: o.raw_cost = true; break;
		case OPT_CONNECT: connect = optarg; break;
		case OPT_TOKEN_FILE: aa_conn_set_token_file(optarg); break;
		case OPT_HELP: fputs(aa_compare_help, stdout); return AA_EXIT_OK;
		default: fputs(aa_compare_help, stderr); return AA_EXIT_USAGE;
		}
	}
	if (argc - optind != 2) {
		fprintf(stderr, "aalab compare: give two runs, BASE and NEW (got %d)\n%s", argc - optind, aa_compare_help);
		return AA_EXIT_USAGE;
	}
	o.base_source = argv[optind];
	o.new_source = argv[optind + 1];
	json_t *base = load_run("BASE", o.base_source, connect);
	json_t *new_run = base ? load_run("NEW", o.new_source, connect) : NULL;
	json_t *cmp = new_run ? aa_compare_results(base, new_run, &o, &err) : NULL;
	json_decref(base);
	json_decref(new_run);
	if (!cmp) {
		if (err.message[0])
			fprintf(stderr, "aalab compare: %s%s%s\n", err.path, err.path[0] ? ": " : "", err.message);
		return err.code == AA_ERR_INTERNAL ? AA_EXIT_FAILED : AA_EXIT_USAGE;
	}
	int status = aa_compare_tripped(cmp) ? AA_EXIT_FAILED : AA_EXIT_OK;
	if ((junit && write_output("junit", junit, cmp, aa_compare_write_junit)) ||
	    (markdown && write_output("markdown", markdown, cmp, aa_compare_write_markdown)))
		status = AA_EXIT_USAGE;
	if (print_json) {
		json_dumpf(cmp, stdout, JSON_INDENT(2));
		fputc('\n', stdout);
	} else {
		aa_compare_print_table(cmp, stdout);
	}
	json_decref(cmp);
	return status;
}
