/* The parts of report.html (report_html.c assembles them): helpers they share, the charts
 * (report_charts.c) and the cards and tables (report_tables.c). Private to engine/report. */
#ifndef AA_REPORT_PARTS_H
#define AA_REPORT_PARTS_H

#include <stdio.h>

#include "results/results.h"

/* Method i's colour, the same in every chart and table. */
const char *aa_report_color(int i);
/* A number with fixed decimals, or a dash when there is none; PSNR, or "identical". */
void aa_report_put_num(FILE *o, double v, int decimals);
void aa_report_put_psnr(FILE *o, double psnr, bool identical);
/* Mean over frames of the share of pixels above threshold t, NAN if no frame has it. */
double aa_report_curve_mean(const struct aa_method_result *m, int t);

void aa_report_chart_cost_accuracy(FILE *o, const struct aa_job_result *r, const struct aa_method_summary *sum,
				   const json_t *verdict);
void aa_report_chart_thresholds(FILE *o, const struct aa_job_result *r);
void aa_report_chart_psnr_per_frame(FILE *o, const struct aa_job_result *r);
/* Each method's GPU time as a bar stacked by pass. */
void aa_report_chart_passes(FILE *o, const struct aa_job_result *r);

void aa_report_summary_cards(FILE *o, const struct aa_job_result *r);
void aa_report_cost_table(FILE *o, const struct aa_job_result *r, const struct aa_method_summary *sum,
			  const json_t *verdict);
void aa_report_plan_table(FILE *o, const struct aa_job_result *r);
void aa_report_method_sections(FILE *o, const struct aa_job_result *r);
/* Every figure of the page explained (report_html.c). */
void aa_report_glossary(FILE *o);

#endif
