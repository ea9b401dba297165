/* libFuzzer target: the job validator (engine/run/job_spec.c) on any JSON text, as submit and aalab run
 * hand it a job object; a valid job must survive a round trip through aa_job_spec_to_json. */
#include <stdint.h>

#include "types/job.h"
#include "run/job_spec.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	json_t *job = json_loadb((const char *)data, size, JSON_DECODE_ANY, NULL);
	if (!job)
		return 0;
	struct aa_job_spec spec;
	struct aa_error err = {0};
	if (aa_job_spec_from_json(job, &spec, &err) == 0) {
		json_t *again = aa_job_spec_to_json(&spec);
		struct aa_job_spec spec2;
		struct aa_error err2 = {0};
		if (!again || aa_job_spec_from_json(again, &spec2, &err2) != 0)
			__builtin_trap(); /* what the validator accepts, it must accept again as it writes it */
		json_decref(again);
	} else if (!err.message[0]) {
		__builtin_trap(); /* a refusal says why */
	}
	json_decref(job);
	return 0;
}
