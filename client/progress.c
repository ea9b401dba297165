/* Progress of a job on the terminal: a bar of steady width with the renders done, the time so far and an
 * estimate of the time left from the renders done; elsewhere (logs, CI, Slurm) a line each time another
 * tenth of the renders is done. */
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "client.h"

static int progress_width;      /* the bar's characters on the line, to erase it */
static double progress_started; /* when the first update came, in seconds; 0: none yet */
static int progress_done0;      /* the renders done at the first update: a watch may join a running job */
static int progress_tenth;      /* the last tenth aa_progress_line printed (0: none yet) */

static double now_seconds(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (double)ts.tv_sec + ts.tv_nsec / 1e9;
}

void aa_format_duration(double seconds, char *out, size_t size)
{
	if (!(seconds >= 0))
		snprintf(out, size, "?");
	else if (seconds < 60)
		snprintf(out, size, "%.0fs", seconds);
	else if (seconds < 3600)
		snprintf(out, size, "%dm%02ds", (int)(seconds / 60), (int)seconds % 60);
	else
		snprintf(out, size, "%dh%02dm", (int)(seconds / 3600), (int)(seconds / 60) % 60);
}

/* "ETA 12s" from the pace of the renders done since the first update; "ETA ?" before there is one. */
static void eta_text(int done, int total, double elapsed, char *out, size_t size)
{
	char t[32];
	if (done <= progress_done0 || done > total) {
		snprintf(out, size, "ETA ?");
		return;
	}
	aa_format_duration(elapsed / (done - progress_done0) * (total - done), t, sizeof t);
	snprintf(out, size, "ETA %s", t);
}

void aa_progress_update(int done, int total, const char *what)
{
	const int bar = 30;
	const double now = now_seconds();
	if (progress_started == 0) {
		progress_started = now;
		progress_done0 = done;
	}
	const double elapsed = now - progress_started;
	int filled = total > 0 ? done * bar / total : 0;
	char line[192], eta[48], spent[32], counts[48];
	int n = 0;
	/* every field has a fixed width, so the bar stays where it is whatever the method's name */
	n += snprintf(line + n, sizeof line - (size_t)n, "\r%-16.16s [", what ? what : "");
	for (int i = 0; i < bar; i++)
		line[n++] = i < filled ? '#' : '.';
	snprintf(counts, sizeof counts, "%d/%d", done, total);
	aa_format_duration(elapsed, spent, sizeof spent);
	eta_text(done, total, elapsed, eta, sizeof eta);
	n += snprintf(line + n, sizeof line - (size_t)n, "] %13s  %7s  %-11s", counts, spent, eta);
	progress_width = n;
	fputs(line, stderr);
	fflush(stderr);
}

void aa_progress_line(const char *cmd, int done, int total, const char *what)
{
	if (total <= 0)
		return;
	if (done < 0)
		done = 0;
	const double now = now_seconds();
	if (progress_started == 0) {
		progress_started = now;
		progress_done0 = done;
	}
	int tenth = done >= total ? 10 : (int)((long)done * 10 / total);
	if (tenth <= progress_tenth)
		return;
	progress_tenth = tenth;
	char eta[48];
	eta_text(done, total, now - progress_started, eta, sizeof eta);
	fprintf(stderr, "aalab %s: %s %d/%d (%d%%, %s)\n", cmd, what, done, total, (int)((long)done * 100 / total), eta);
	fflush(stderr);
}

double aa_progress_seconds(void)
{
	return progress_started == 0 ? 0 : now_seconds() - progress_started;
}

void aa_progress_finish(void)
{
	progress_tenth = 0;
	progress_started = 0;
	progress_done0 = 0;
	if (progress_width) {
		fprintf(stderr, "\r%*s\r", progress_width, "");
		progress_width = 0;
	}
}
