/* aalab: the client. Dispatches subcommands; each is one entry of the table below. */
#include <stdio.h>
#include <string.h>

#include "client.h"

static const struct aa_cmd_entry commands[] = {
	{"run", "run [JOB.json] [--scene NAME] [--path PATH] [--methods LIST] [--frames N] [--size WxH] "
		"[--reference-samples N] [--out DIR] [--device SEL] [--no-images] [--json] [--quiet]",
	 "render a comparison job in this process and write results, images and a report", cmd_run},
	{"scenes", "scenes [--json]", "list the scenes that can be named with --scene", cmd_scenes},
	{"methods", "methods [--json]", "list the AA methods with their parameters, defaults and valid values",
	 cmd_methods},
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
				printf("usage: aalab %s\n\n%s\n", commands[i].usage, commands[i].summary);
				return AA_EXIT_OK;
			}
			return commands[i].exec(argc - 1, argv + 1);
		}
	fprintf(stderr, "aalab: unknown command '%s'\n", argv[1]);
	usage(stderr);
	return AA_EXIT_USAGE;
}
