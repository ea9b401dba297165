/* aalab: the client. Dispatches subcommands; each is one entry of the table below. */
#include <stdio.h>
#include <string.h>

#include "client.h"

static const struct aa_cmd_entry commands[] = {
	/* name, summary, exec, full help (every command has one: 'aalab COMMAND --help') */
	{"run", "render a comparison job and write results, images and a report",
	 cmd_run, aa_run_help},
	{"scenes", "list the scenes that can be named with --scene", cmd_scenes,
	 "usage: aalab " AA_SCENES_USAGE "\n\n"
	 "Lists the scenes that --scene can name (from their JSON alone: no mesh is loaded), each with its\n"
	 "objects, every camera path and its description. With a NAME or a scene file, loads that scene and\n"
	 "describes it: triangles, objects, materials, textures, paths, the animations of its mesh files, the\n"
	 "files it reads (meshes, what they name, textures) and what loading dropped (warnings).\n\n"
	 "  --json                  print the same as JSON\n\n"
	 "Exit status: 0 listed, 2 an unknown option or scene, a second name or a scene file that does not load.\n"},
	{"suites", "list the suites that 'aalab run SUITE' finds by name", cmd_suites,
	 "usage: aalab " AA_SUITES_USAGE "\n\n"
	 "Lists the suites that 'aalab run SUITE' finds by name ($AALAB_SUITE_DIR, the source tree's suites/,\n"
	 "the installed ones): each with its cases, methods, description and file.\n\n"
	 "  --json                  print the same as JSON\n\n"
	 "Exit status: 0 listed, 2 an unknown option or an argument.\n"},
	{"methods", "list the AA methods with their parameters, defaults and valid values",
	 cmd_methods,
	 "usage: aalab " AA_METHODS_USAGE "\n\n"
	 "Lists the AA methods (only those named, when names are given), each with its seed and its parameters:\n"
	 "type, default, valid values and what it does.\n\n"
	 "  --json                  print the same as JSON\n\n"
	 "Exit status: 0 listed, 2 an unknown option or method (the closest known one is named).\n"},
	{"submit", "queue a job on aalabd and print its id", cmd_submit,
	 aa_submit_help},
	{"watch", "follow a job on aalabd until it ends", cmd_watch, aa_watch_help},
	{"status", "show a job's verdict, state, progress and summary", cmd_status,
	 aa_status_help},
	{"list", "list the jobs aalabd holds", cmd_jobs, aa_list_help},
	{"cancel", "cancel a queued or running job and print its new state", cmd_cancel,
	 aa_cancel_help},
	{"get", "download a job's results, report and frames", cmd_get, aa_get_help},
	{"diff",
	 "compare two image files (PSNR, SSIM, FLIP, Fourier bands) and gate on thresholds", cmd_diff, aa_diff_help},
	{"compare", "compare two runs per case and method, and gate on quality and cost",
	 cmd_compare, aa_compare_help},
	{"merge",
	 "join the result folders of a job's shards into the results of the whole job", cmd_merge, aa_merge_help},
	{"cache", "show, clear or verify the store of reference frames runs share", cmd_cache, aa_cache_help},
	{"slurm",
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
				fputs(commands[i].help, stdout);
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
