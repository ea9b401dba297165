/* report.html's warnings panel, at the top of the page: everything in the job that makes a number below
 * less trustworthy than it looks, said once and plainly (a noisy reference, times too spread to rank two
 * methods, NaN/Inf in an output, no GPU timestamps) and what loading the scene dropped or approximated. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "results/results.h"
#include "report/report.h"

/* Under this convergence PSNR the reference's own noise is visible in method PSNRs. */
#define CONVERGED_DB 40.0

static void esc_text(FILE *o, const char *s)
{
	for (; s && *s; s++) {
		switch (*s) {
		case '&': fputs("&amp;", o); break;
		case '<': fputs("&lt;", o); break;
		case '>': fputs("&gt;", o); break;
		case '"': fputs("&quot;", o); break;
		default: fputc((unsigned char)*s < 0x20 ? ' ' : *s, o);
		}
	}
}

static int by_median(const void *a, const void *b, void *sum)
{
	const struct aa_method_summary *s = sum;
	const double x = s[*(const int *)a].gpu_ms.median, y = s[*(const int *)b].gpu_ms.median;
	return (x > y) - (x < y);
}

static void item_begin(FILE *o, int *count)
{
	if ((*count)++ == 0)
		fputs("<section id=\"warnings\" class=\"warnings\"><h2>Warnings</h2><ul>\n", o);
	fputs("<li>", o);
}

void aa_report_write_warnings(FILE *o, const struct aa_job_result *r, const struct aa_method_summary *sum)
{
	int count = 0;
	/* what loading the scene dropped or approximated: every number below is for the scene as drawn */
	for (int i = 0; i < r->warning_count && i < AA_MAX_WARNINGS; i++) {
		item_begin(o, &count);
		fputs("<b>Scene</b>: ", o);
		esc_text(o, r->warnings[i]);
		fputs(" (the numbers are for the scene as drawn)</li>\n", o);
	}
	if (r->warnings_dropped > 0) {
		item_begin(o, &count);
		fprintf(o, "... and %d more scene warnings (results.json lists them)</li>\n", r->warnings_dropped);
	}
	bool identical;
	const double conv = aa_reference_convergence_psnr(&r->reference, &identical);
	if (isfinite(conv) && conv < CONVERGED_DB) {
		item_begin(o, &count);
		if (r->reference.auto_samples)
			fprintf(o, "<b>The reference is not converged</b>: with <code>reference.samples</code> \"auto\" "
				   "(cap %d) its N/2-sample images differ from its N-sample images by %.1f dB PSNR "
				   "(under %.0f dB). Method PSNRs near or above %.1f dB measure the reference's noise, "
				   "not the method; raise <code>reference.max_samples</code>.</li>\n",
				r->reference.samples, conv, CONVERGED_DB, conv);
		else
			fprintf(o, "<b>The reference is not converged</b>: its %d-sample image differs from its "
				   "%d-sample image by %.1f dB PSNR (under %.0f dB). Method PSNRs near or above %.1f dB "
				   "measure the reference's noise, not the method; raise <code>reference.samples</code>."
				   "</li>\n", r->reference.samples / 2, r->reference.samples, conv, CONVERGED_DB, conv);
		for (int i = 0; i < r->method_count; i++)
			if (isfinite(sum[i].psnr_mean) && sum[i].psnr_mean >= conv - 3.0) {
				item_begin(o, &count);
				esc_text(o, r->methods[i].label);
				fprintf(o, " scores %.1f dB, within 3 dB of the reference's own convergence (%.1f dB): its "
					   "PSNR is not meaningful here.</li>\n", sum[i].psnr_mean, conv);
			}
	}
	/* reference.samples "auto": frames that stopped at the cap short of the target */
	int capped = 0;
	for (int f = 0; r->reference.auto_samples && r->reference.frames && f < r->reference.frame_count; f++) {
		const struct aa_reference_frame *rf = &r->reference.frames[f];
		capped += !rf->reused && !rf->convergence_identical && rf->samples >= r->reference.samples &&
			  !(rf->convergence_psnr >= r->reference.target_psnr);
	}
	if (capped) {
		item_begin(o, &count);
		fprintf(o, "<b>Reference capped</b>: %d frame%s reached <code>reference.max_samples</code> (%d) before "
			   "the target of %.1f dB (results.json: reference.frames[].convergence_psnr).</li>\n", capped,
			capped == 1 ? "" : "s", r->reference.samples, r->reference.target_psnr);
	}
	/* Neighbours in the ranking by median GPU time whose p10-p90 ranges overlap cannot be ranked. */
	int order[AA_MAX_METHODS], timed = 0;
	for (int i = 0; i < r->method_count && i < AA_MAX_METHODS; i++)
		if (isfinite(sum[i].gpu_ms.median) && isfinite(sum[i].gpu_ms.p10) && isfinite(sum[i].gpu_ms.p90))
			order[timed++] = i;
	qsort_r(order, (size_t)timed, sizeof order[0], by_median, (void *)sum);
	for (int k = 1; k < timed; k++) {
		const struct aa_method_summary *a = &sum[order[k - 1]], *b = &sum[order[k]];
		if (a->gpu_ms.p90 < b->gpu_ms.p10)
			continue;
		item_begin(o, &count);
		fputs("<b>Timing too spread to rank</b> ", o);
		esc_text(o, r->methods[order[k - 1]].label);
		fputs(" and ", o);
		esc_text(o, r->methods[order[k]].label);
		fprintf(o, ": their GPU times overlap (p10&ndash;p90 %.2f&ndash;%.2f ms, n %d, against %.2f&ndash;%.2f ms, "
			   "n %d). Raise <code>timing.repeat</code> or treat them as equal in cost.</li>\n",
			a->gpu_ms.p10, a->gpu_ms.p90, a->gpu_ms.n, b->gpu_ms.p10, b->gpu_ms.p90, b->gpu_ms.n);
	}
	if (!isfinite(r->timestamp_period_ns)) {
		item_begin(o, &count);
		fputs("<b>No GPU timestamps</b> on this device: GPU times are missing, only CPU times are shown.</li>\n", o);
	}
	for (int i = 0; i < r->method_count; i++) {
		long bad = 0;
		for (int f = 0; f < r->methods[i].frame_count; f++)
			bad += r->methods[i].frames[f].nonfinite;
		if (bad > 0) {
			item_begin(o, &count);
			esc_text(o, r->methods[i].label);
			fprintf(o, " wrote <b>%ld NaN or Inf values</b>: its output is broken.</li>\n", bad);
		}
	}
	long ref_bad = 0;
	for (int f = 0; r->reference.frames && f < r->reference.frame_count; f++)
		ref_bad += r->reference.frames[f].nonfinite;
	if (ref_bad > 0) {
		item_begin(o, &count);
		fprintf(o, "The reference wrote <b>%ld NaN or Inf values</b>: every comparison is suspect.</li>\n", ref_bad);
	}
	if (count)
		fputs("</ul></section>\n", o);
}
