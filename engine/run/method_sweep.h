/* Sweeps (docs/job-format.md, "Sweeps"): one item of a job's "methods" that names several values of one or
 * more parameters, "fxaa:preset=10|20|39", "msaa:2|4|8" or {"name": "msaa", "params": {"samples": [2, 4, 8]}},
 * stands for one method per configuration: the cartesian product across its parameters, the last one
 * varying fastest. Each configuration is written back as the item that names it alone, so that it is
 * parsed and validated as any other method. */
#ifndef AA_METHOD_SWEEP_H
#define AA_METHOD_SWEEP_H

#include <jansson.h>

#include "util/error.h"

/* The configurations item (the job's field path, "methods[2]") stands for, as a new array of items: the
 * item itself when it is no sweep. room is how many more methods the job takes; a sweep past it is an
 * AA_ERR_LIMIT error that names the parameter whose values pass it. NULL with err set on an error. */
json_t *aa_method_sweep_expand(const json_t *item, const char *path, int room, struct aa_error *err);

#endif
