/* The aalab command-line client: one file per group of subcommands, each an entry in aalab.c's table. */
#ifndef AA_CLIENT_H
#define AA_CLIENT_H

#include <stdbool.h>

#include "job.h"

struct aa_cmd_entry {
	const char *name;
	const char *usage;
	const char *summary;
	int (*exec)(int argc, char **argv);
};

/* Exit statuses: 0 success, 1 the work failed (or a --fail-above gate tripped), 2 bad usage or input. */
#define AA_EXIT_OK 0
#define AA_EXIT_FAILED 1
#define AA_EXIT_USAGE 2

int cmd_run(int argc, char **argv);
int cmd_scenes(int argc, char **argv);
int cmd_methods(int argc, char **argv);

/* table.c: the cost-vs-accuracy table and progress display */
void aa_print_table(const struct aa_job_result *r, FILE *out);
void aa_progress_update(int done, int total, const char *what);
void aa_progress_finish(void);

/* Splits a --methods value into method strings: commas separate methods, except that a "key=value"
 * token without ':' continues the previous method's parameters ("fxaa:preset=12,subpix=0.5,none"). */
int aa_split_methods(const char *text, char ***out, int *count);
void aa_free_strings(char **v, int count);

#endif
