/* aalab: the client. Dispatches subcommands; each is one entry of the table below. */
#include <stdio.h>
#include <string.h>

#include "client.h"

static const struct aa_cmd_entry commands[] = {
	/* name, usage, summary, exec[, full help] */
	{"run", "run [JOB.json|SUITE] [--scene NAME] [--path PATH] [--methods LIST] [--frames N] [--size WxH] "
		"[--reference-samples N] [--repeat N] [--over-threshold X] [--label KEY=VALUE] [--out DIR] [--device SEL] "
		"[--no-images] [--no-viewer] [--exr] [--json] [--quiet] [--shard I/N] [--reference-cache DIR|off] "
		"[--reference-cache-size SIZE] [--explain-key]",
	 "render a comparison job and write results, images and a report", cmd_run, aa_run_help},
	{"scenes", AA_SCENES_USAGE, "list the scenes that can be named with --scene", cmd_scenes,
	 "usage: aalab " AA_SCENES_USAGE "\n\n"
	 "Lists the scenes that --scene can name (from their JSON alone: no mesh is loaded), each with its\n"
	 "objects, camera paths and description. With a NAME or a scene file, loads that scene and describes\n"
	 "it: triangles, objects, materials, textures, paths, the animations of its mesh files, the files it\n"
	 "reads (meshes, what they name, textures) and what loading dropped (warnings). --json prints the same\n"
	 "as JSON.\n"},
	{"suites", AA_SUITES_USAGE, "list the suites that 'aalab run SUITE' finds by name", cmd_suites, NULL},
	{"methods", AA_METHODS_USAGE, "list the AA methods with their parameters, defaults and valid values",
	 cmd_methods,
	 "usage: aalab " AA_METHODS_USAGE "\n\n"
	 "Lists the AA methods (only those named, when names are given), each with its seed and its parameters:\n"
	 "type, default, valid values and what it does. --json prints the same as JSON. An unknown name exits 2.\n"},
	{"submit", "submit [JOB.json] [job flags of run] [--scene-file FILE] [--watch] [--connect ADDRESS] [--json]",
	 "queue a job on aalabd and print its id", cmd_submit, NULL},
	{"watch", "watch JOB [--after SEQ] [--connect ADDRESS] [--json]", "follow a job on aalabd until it ends",
	 cmd_watch, NULL},
	{"status", "status JOB [--connect ADDRESS] [--json]", "show a job's state, progress and summary", cmd_status, NULL},
	{"list", "list [--state STATE] [--connect ADDRESS] [--json]", "list the jobs aalabd holds", cmd_jobs, NULL},
	{"cancel", "cancel JOB [--connect ADDRESS] [--json]", "cancel a queued or running job", cmd_cancel, NULL},
	{"get", "get JOB [--out DIR] [--file NAME] [--no-images] [--connect ADDRESS] [--json]",
	 "download a job's results, report and frames", cmd_get, NULL},
	{"diff", "diff REF TEST [--metrics psnr,ssim,flip,fourier] [--json] [--error-map OUT.png] "
		 "[--fail-above NAME=X ...] [--fail-below NAME=X ...] [--ppd X]",
	 "compare two image files (PSNR, SSIM, FLIP, Fourier bands) and gate on thresholds", cmd_diff, aa_diff_help},
	{"compare", "compare BASE NEW [--fail-if GATE ...] [--json] [--junit FILE] [--markdown FILE] [--allow-missing]",
	 "compare two runs per case and method, and gate on quality and cost", cmd_compare, aa_compare_help},
	{"merge", "merge --out DIR SHARD_DIR... [--force] [--json] [--quiet]",
	 "join the result folders of a job's shards into the results of the whole job", cmd_merge, aa_merge_help},
	{"cache", "cache stats|clear|verify [--sample N] [--reference-cache DIR] [--json]",
	 "show, clear or verify the store of reference frames runs share", cmd_cache, aa_cache_help},
	{"slurm", "slurm [JOB.json] [job flags of run] --shards N --out DIR [--partition P] [--gres G] [--time T] "
		  "[--reference-cache DIR|off] [--submit]",
	 "write (and submit) a Slurm array job of a job's shards and the job that merges them", cmd_slurm, aa_slurm_help},
};

static void usage(FILE *out)
{
	fprintf(out, "usage: aalab COMMAND [ARGS]\n\ncommands:\n");
	for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
		fprintf(out, "  %-8s %s\n", commands[i].name, commands[i].summary);
	fprintf(out, "\n'aalab COMMAND --help' describes a command. See aalab(1).\n");
}

int main(int argc, char **argv)
{
	if (argc < 2) {
		usage(stderr);
		return AA_EXIT_USAGE;
	}
	if (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0 || strcmp(argv[1], "help") == 0) {
		usage(stdout);
		return AA_EXIT_OK;
	}
	if (strcmp(argv[1], "--version") == 0) {
		printf("aalab %s\n", PACKAGE_VERSION);
		return AA_EXIT_OK;
	}
	for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
		if (strcmp(argv[1], commands[i].name) == 0) {
			if (argc > 2 && (strcmp(argv[2], "--help") == 0 || strcmp(argv[2], "-h") == 0)) {
				if (commands[i].help)
					fputs(commands[i].help, stdout);
				else
					printf("usage: aalab %s\n\n%s\n", commands[i].usage, commands[i].summary);
				return AA_EXIT_OK;
			}
			/* getopt names argv[0] in its messages: "aalab run: unrecognized option", as our own say */
			char name[64];
			snprintf(name, sizeof name, "aalab %s", commands[i].name);
			argv[1] = name;
			return commands[i].exec(argc - 1, argv + 1);
		}
	fprintf(stderr, "aalab: unknown command '%s'\n", argv[1]);
	usage(stderr);
	return AA_EXIT_USAGE;
}
