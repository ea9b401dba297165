/* results.json's warnings[] (docs/results-format.md, "warnings"): everything in a run that makes a number
 * less trustworthy than it looks, each with a code, a message and what to do about it. The terminal,
 * report.html and the dashboard print this list as it is. */
#ifndef AA_WARNINGS_H
#define AA_WARNINGS_H

#include <jansson.h>

#include "results/results.h"

/* Under this convergence PSNR the reference's own noise shows in the methods' PSNRs. */
#define AA_REFERENCE_CONVERGED_DB 40.0
/* A method whose PSNR is within this of the reference's convergence PSNR measures the reference's noise. */
#define AA_REFERENCE_NOISE_MARGIN_DB 3.0

/* [{"code", "message", "action"}] of one job (or case), given its verdict object (aa_verdict_json), whose
 * cost ties and unranked methods it warns about. NULL when out of memory. */
json_t *aa_results_warnings_json(const struct aa_job_result *r, const json_t *verdict);

#endif
