/* aalab suites: the suites 'aalab run SUITE' finds by name, with their cases and methods. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "client.h"
#include "run/farm.h"
#include "methods/user_method.h"
#include "run/job_spec.h"

int cmd_suites(int argc, char **argv)
{
	bool json;
	int unused, status = aa_list_args("suites", AA_SUITES_USAGE, argc, argv, 0, &json, &unused);
	if (status)
		return status;
	char **names;
	int count;
	if (aa_suite_list(&names, &count)) {
		fprintf(stderr, "aalab suites: cannot list suites\n");
		return AA_EXIT_FAILED;
	}
	json_t *arr = json_array();
	for (int i = 0; i < count; i++) {
		char file[1200];
		struct aa_error err = {0};
		struct aa_job_spec *spec = calloc(1, sizeof *spec);
		json_t *o = json_pack("{ss}", "name", names[i]), *job = NULL;
		if (spec && aa_suite_resolve(names[i], file, sizeof file, &err) == 0 &&
		    (job = json_load_file(file, JSON_REJECT_DUPLICATES, NULL)) &&
		    /* user methods are read as aalab run reads them (docs/user-methods.md) */
		    aa_job_spec_from_json_files(job, &aa_file_source_disk, spec, &err) == 0) {
			json_object_set_new(o, "file", json_string(file));
			json_object_set_new(o, "cases", json_integer(aa_job_case_count(spec)));
			json_object_set_new(o, "methods", json_integer(spec->method_count));
			json_object_set_new(o, "description", json_string(spec->name));
			if (!json)
				printf("%-12s %3d cases x %2d methods  %s\n%12s %s\n", names[i], aa_job_case_count(spec),
				       spec->method_count, spec->name, "", file);
		} else {
			const char *why = err.message[0] ? err.message : "not a valid job file";
			json_object_set_new(o, "error", json_string(why));
			if (!json)
				printf("%-12s (invalid: %s%s%s)\n", names[i], err.path, err.path[0] ? ": " : "", why);
		}
		json_decref(job);
		if (spec)
			aa_job_spec_release(spec); /* a suite's user methods, also those read before an error */
		free(spec);
		json_array_append_new(arr, o);
	}
	if (json) {
		json_dumpf(arr, stdout, JSON_INDENT(2));
		fputc('\n', stdout);
	}
	json_decref(arr);
	aa_free_strings(names, count);
	return AA_EXIT_OK;
}
