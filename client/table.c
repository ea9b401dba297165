/* Terminal output of the client: the cost-vs-accuracy table, the progress bar, and --methods splitting. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "client.h"
#include "methods/methods.h"
#include "results/results.h"

static void format_psnr(double psnr, bool identical, char *out, size_t size)
{
	if (identical)
		snprintf(out, size, "identical");
	else if (isnan(psnr))
		snprintf(out, size, "-");
	else
		snprintf(out, size, "%.2f", psnr);
}

/* ", from the cache: 28 of 30 frames" when the run had a store (the frames it did not render). */
static void cache_text(const struct aa_job_result *r, char *out, size_t size)
{
	const struct aa_reference_cache_result *c = &r->reference.cache;
	out[0] = 0;
	if (!c->used)
		return;
	int n = snprintf(out, size, ", from the cache: %d of %d frames", c->hits, r->reference.frame_count);
	if (c->continued && n > 0 && (size_t)n < size)
		snprintf(out + n, size - (size_t)n, " (%d went on from a stored sum)", c->continued);
}

void aa_print_table(const struct aa_job_result *r, FILE *out)
{
	char cached[96];
	cache_text(r, cached, sizeof cached);
	double conv_mse = 0;
	for (int f = 0; f < r->reference.frame_count; f++)
		conv_mse += r->reference.frames[f].convergence_mse;
	conv_mse /= r->reference.frame_count > 0 ? r->reference.frame_count : 1;
	char conv[32];
	format_psnr(aa_psnr_from_mse(conv_mse, 255.0), conv_mse == 0.0, conv, sizeof conv);
	if (r->reference.auto_samples) {
		/* the N each frame reached, as a range: "auto" alone would hide what the reference cost */
		int lo = 0, hi = 0, capped = 0;
		for (int f = 0; f < r->reference.frame_count; f++) {
			const struct aa_reference_frame *rf = &r->reference.frames[f];
			lo = f == 0 || rf->samples < lo ? rf->samples : lo;
			hi = rf->samples > hi ? rf->samples : hi;
			capped += rf->samples >= r->reference.samples && !rf->convergence_identical &&
				  !(rf->convergence_psnr >= r->reference.target_psnr);
		}
		char reached[96];
		snprintf(reached, sizeof reached, lo == hi ? "%d samples" : "%d-%d samples per frame", lo, hi);
		fprintf(out, "scene %s, path %s, %dx%d, %d frame%s, reference auto: %s (target %.1f dB, cap %d; "
			"convergence N/2 vs N: %s dB", r->scene_name, r->spec.path, r->spec.width, r->spec.height,
			r->spec.frames, r->spec.frames == 1 ? "" : "s", reached, r->reference.target_psnr,
			r->reference.samples, conv);
		if (capped)
			fprintf(out, "; %d frame%s stopped at the cap under the target", capped, capped == 1 ? "" : "s");
		fprintf(out, ")%s, %s\n\n", cached, r->device_name);
	} else {
		fprintf(out, "scene %s, path %s, %dx%d, %d frame%s, reference %d samples%s (convergence %d vs %d: "
			"%s dB), %s\n\n", r->scene_name, r->spec.path, r->spec.width, r->spec.height, r->spec.frames,
			r->spec.frames == 1 ? "" : "s", r->reference.samples, cached, r->reference.samples / 2,
			r->reference.samples, conv, r->device_name);
	}
	bool sequence = r->spec.frames > 1;
	/* GPU time over every timed render (frames x --repeat): median, the 10th-90th percentile range, count */
	char over_head[24]; /* idiff's count: pixels with a channel off by more than the threshold */
	snprintf(over_head, sizeof over_head, "%%px >%g", r->spec.over_threshold);
	int width = 24; /* the method column fits the longest label, so parameters do not push the columns */
	for (int i = 0; i < r->method_count; i++)
		width = (int)strlen(r->methods[i].label) > width ? (int)strlen(r->methods[i].label) : width;
	fprintf(out, "%-*s %12s %15s %4s %9s %10s %8s %10s", width, "method", "GPU ms/frame", "p10-p90 ms", "n", "MB",
		"PSNR dB", "SSIM", over_head);
	if (sequence) /* per-sequence figures: worst and best frame (index), and the temporal stability figure */
		fprintf(out, " %16s %16s %8s", "worst dB (frame)", "best dB (frame)", "flicker");
	fputc('\n', out);
	for (int i = 0; i < r->method_count; i++) {
		const struct aa_method_result *m = &r->methods[i];
		struct aa_method_summary s;
		aa_method_summarize(m, &s);
		char psnr[32];
		format_psnr(s.psnr_mean, s.psnr_identical, psnr, sizeof psnr);
		char spread[48];
		snprintf(spread, sizeof spread, "%.2f-%.2f", s.gpu_ms.p10, s.gpu_ms.p90);
		fprintf(out, "%-*s %12.2f %15s %4d %9.1f %10s %8.4f %10.2f", width, m->label, s.gpu_ms.median, spread,
			s.gpu_ms.n, m->memory_bytes / (1024.0 * 1024.0), psnr, s.ssim_mean,
			100.0 * s.over_threshold_mean / ((double)r->spec.width * r->spec.height));
		if (sequence) {
			char worst[32], best[32], text[48];
			format_psnr(s.worst_psnr, false, worst, sizeof worst);
			format_psnr(s.best_psnr, isnan(s.best_psnr), best, sizeof best);
			snprintf(text, sizeof text, "%s (%d)", worst, s.worst_frame);
			fprintf(out, " %16s", text);
			snprintf(text, sizeof text, "%s (%d)", best, s.best_frame);
			fprintf(out, " %16s %8.3f", text, s.flicker_mean);
		}
		fputc('\n', out);
	}
	/* cut-out materials: say how each method tested alpha, so that a ranking can be read fairly */
	bool cutouts = false;
	for (int i = 0; i < r->plan_count && i < AA_MAX_PASSES; i++)
		cutouts = cutouts || (strcmp(r->plan[i].pass, "alpha-test") == 0 && r->plan[i].ran);
	if (cutouts) {
		fputs("\nalpha test of cut-out materials:", out);
		for (int i = 0; i < r->method_count; i++)
			fprintf(out, "%s %s %s", i ? "," : "", r->methods[i].label,
				aa_alpha_rule_name(aa_method_alpha_rule(r->methods[i].method, &r->methods[i].params)));
		fputs("; reference per-sample (docs/methods.md)\n", out);
	}
	if (r->warning_count > 0) {
		fprintf(out, "\nwarnings (what the scene draws differently from its files):\n");
		for (int i = 0; i < r->warning_count && i < AA_MAX_WARNINGS; i++)
			fprintf(out, "  %s\n", r->warnings[i]);
		if (r->warnings_dropped > 0)
			fprintf(out, "  ... and %d more\n", r->warnings_dropped);
	}
}

static int progress_width;

void aa_progress_update(int done, int total, const char *what)
{
	const int bar = 30;
	int filled = total > 0 ? done * bar / total : 0;
	char line[128];
	int n = snprintf(line, sizeof line, "\r%s [", what);
	for (int i = 0; i < bar; i++)
		line[n++] = i < filled ? '#' : '.';
	n += snprintf(line + n, sizeof line - (size_t)n, "] %d/%d", done, total);
	progress_width = n;
	fputs(line, stderr);
	fflush(stderr);
}

static int progress_tenth; /* the last tenth aa_progress_line printed (0: none yet) */

void aa_progress_line(const char *cmd, int done, int total, const char *what)
{
	if (total <= 0)
		return;
	if (done < 0)
		done = 0;
	int tenth = done >= total ? 10 : (int)((long)done * 10 / total);
	if (tenth <= progress_tenth)
		return;
	progress_tenth = tenth;
	fprintf(stderr, "aalab %s: %s %d/%d (%d%%)\n", cmd, what, done, total, (int)((long)done * 100 / total));
	fflush(stderr);
}

void aa_progress_finish(void)
{
	progress_tenth = 0;
	if (progress_width) {
		fprintf(stderr, "\r%*s\r", progress_width, "");
		progress_width = 0;
	}
}

void aa_free_strings(char **v, int count)
{
	for (int i = 0; i < count; i++)
		free(v[i]);
	free(v);
}

int aa_split_methods(const char *text, char ***out, int *count)
{
	char *copy = strdup(text);
	char **list = calloc(strlen(text) + 1, sizeof *list);
	int n = 0;
	if (!copy || !list) {
		free(copy);
		free(list);
		return -1;
	}
	char *save = NULL;
	for (char *tok = strtok_r(copy, ", \t", &save); tok; tok = strtok_r(NULL, ", \t", &save)) {
		bool continues = n > 0 && strchr(tok, '=') && !strchr(tok, ':');
		if (continues) {
			size_t len = strlen(list[n - 1]) + strlen(tok) + 2;
			char *joined = malloc(len);
			if (!joined)
				break;
			snprintf(joined, len, "%s,%s", list[n - 1], tok);
			free(list[n - 1]);
			list[n - 1] = joined;
		} else {
			list[n++] = strdup(tok);
		}
	}
	free(copy);
	*out = list;
	*count = n;
	return 0;
}
