/* aalab run's output folder: results are written to a temporary folder beside it and renamed into place
 * when complete, so a folder is either a whole aalab result or untouched. */
#ifndef AALAB_OUT_DIR_H
#define AALAB_OUT_DIR_H

#include <stdbool.h>
#include <stddef.h>

struct aa_out_dir {
	char final[1024];    /* where the results go (--out DIR) */
	char work[2100];     /* the temporary folder written to: DIR's parent/.DIR.aalab-partial.XXXXXX */
	bool replace;        /* final holds an earlier aalab result that --force replaces */
};

/* Checks DIR and makes the temporary folder. Refuses (message in err, naming DIR) a path that is not a
 * folder, a non-empty folder that is not an aalab result, and an earlier aalab result without force. */
int aa_out_dir_prepare(struct aa_out_dir *o, const char *dir, bool force, char *err, size_t err_size);
/* Puts the complete results in place (replacing an earlier result with --force). */
int aa_out_dir_commit(struct aa_out_dir *o, char *err, size_t err_size);
/* Removes the temporary folder (a failed job: half a result is no result). */
void aa_out_dir_discard(struct aa_out_dir *o);
/* Ctrl-C (SIGINT) and SIGTERM from here on print what was kept (the temporary folder, with the frames
 * written so far: frames_written, counted by the caller, or NULL when the job runs on aalabd) and exit 130. */
void aa_out_dir_on_interrupt(struct aa_out_dir *o, bool in_daemon, volatile int *frames_written, int frames_total);

#endif
