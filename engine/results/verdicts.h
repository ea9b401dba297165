/* Verdicts on a hard-case suite (docs/hard-cases.md): for every case and method, computed from the frames,
 * each verdict pass, fail or not applicable, failures the docs expect (with their reason) told apart. */
#ifndef AA_VERDICTS_H
#define AA_VERDICTS_H

#include <jansson.h>

#include "run/farm.h"

enum aa_verdict_kind {
	AA_VERDICT_FINITE,  /* no NaN/Inf in any frame's float output (debug_targets: nor in an intermediate) */
	AA_VERDICT_RANGE,   /* no negative R, G or B (below -1/1024) in any frame */
	AA_VERDICT_STUCK,   /* not stuck: it changes at least STUCK_RATIO as much as the reference does */
	AA_VERDICT_DRIFT,   /* static path where nothing moves (the reference is reused), >= 16 frames: the last
			     * quarter's PSNR not below the second quarter's by more than DRIFT_DB */
	AA_VERDICT_VS_NONE, /* PSNR not below `none`'s by more than VS_NONE_DB */
	AA_VERDICT_DIP,     /* in no frame is the PSNR below `none`'s in that frame by more than DIP_DB: a short
			     * drop the case's mean hides (a ghost after a cut or a jump, a firefly held) */
	AA_VERDICT_COUNT
};
enum aa_verdict_state { AA_VERDICT_NA, AA_VERDICT_PASS, AA_VERDICT_FAIL };

#define AA_VERDICT_STUCK_RATIO 0.1   /* of the reference's change, in frames where it changes >= 1/255 */
#define AA_VERDICT_STUCK_MIN_CHANGE 1.0
#define AA_VERDICT_DRIFT_DB 0.5
#define AA_VERDICT_DRIFT_MIN_FRAMES 16
#define AA_VERDICT_VS_NONE_DB 1.0
#define AA_VERDICT_DIP_DB 1.5

struct aa_verdict {
	enum aa_verdict_state state[AA_VERDICT_COUNT];
	double value[AA_VERDICT_COUNT];   /* the figure judged (count, ratio or dB) */
	const char *expected[AA_VERDICT_COUNT]; /* a failure docs/hard-cases.md expects: its reason */
	int dip_frame;                    /* the frame (index on the path) of value[AA_VERDICT_DIP] */
};

const char *aa_verdict_name(enum aa_verdict_kind k);
/* Method m of one case. */
void aa_verdict_judge(const struct aa_job_result *c, int m, struct aa_verdict *out);
/* The reason docs/hard-cases.md gives for a failure of kind k of method m run with params p on scene, or
 * NULL when the failure is not expected (an exception may hold for one value of a parameter only). */
const char *aa_verdict_expected(const char *scene, const struct aa_method *m, const struct aa_method_params *p,
				enum aa_verdict_kind k);
/* {"failed": N, "expected_failures": N, "items": [{"case", "method", "verdicts": {kind: {"state",
 * "value", "expected"?}}}]}; *failed (may be NULL) is the count of failures not expected. */
json_t *aa_verdicts_json(const struct aa_suite_result *r, int *failed);

#endif
