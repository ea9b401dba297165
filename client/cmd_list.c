/* aalab scenes / aalab methods: what a job can name, with parameters, defaults and valid values. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "client.h"
#include "methods/method.h"
#include "scene/scene.h"

static bool want_json(int argc, char **argv)
{
	for (int i = 1; i < argc; i++)
		if (strcmp(argv[i], "--json") == 0)
			return true;
	return false;
}

int cmd_scenes(int argc, char **argv)
{
	char **names;
	int count;
	if (aa_scene_list(&names, &count)) {
		fprintf(stderr, "aalab scenes: cannot list scenes\n");
		return AA_EXIT_FAILED;
	}
	bool json = want_json(argc, argv);
	json_t *arr = json_array();
	for (int i = 0; i < count; i++) {
		char file[1024];
		struct aa_error err = {0};
		struct aa_scene *s = NULL;
		json_t *o = json_pack("{ss}", "name", names[i]);
		if (aa_scene_resolve(names[i], file, sizeof file, &err) == 0 && aa_scene_load(file, &s, &err) == 0) {
			json_t *paths = json_array();
			for (int p = 0; p < s->path_count; p++)
				json_array_append_new(paths, json_string(s->paths[p].name));
			json_object_set_new(o, "file", json_string(file));
			json_object_set_new(o, "description", json_string(s->description));
			json_object_set_new(o, "triangles", json_integer((json_int_t)aa_scene_triangle_count(s)));
			json_object_set_new(o, "paths", paths);
			if (!json)
				printf("%-16s %7llu triangles  paths: default, static%s%s\n%16s %s\n", names[i],
				       (unsigned long long)aa_scene_triangle_count(s), s->path_count ? ", " : "",
				       s->path_count ? s->paths[0].name : "", "", s->description);
			aa_scene_free(s);
		} else {
			json_object_set_new(o, "error", json_string(err.message));
			if (!json)
				printf("%-16s (invalid: %s)\n", names[i], err.message);
		}
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

static const char *type_name(enum aa_param_type t)
{
	switch (t) {
	case AA_PARAM_INT: return "int";
	case AA_PARAM_FLOAT: return "float";
	case AA_PARAM_ENUM: return "enum";
	case AA_PARAM_BOOL: return "bool";
	}
	return "?";
}

static void valid_values(const struct aa_param_def *d, char *out, size_t size)
{
	size_t n = 0;
	out[0] = 0;
	if (d->allowed) {
		for (int i = 0; d->allowed[i]; i++)
			n += (size_t)snprintf(out + n, n < size ? size - n : 0, "%s%d", i ? ", " : "", d->allowed[i]);
	} else if (d->choices) {
		for (int i = 0; d->choices[i]; i++)
			n += (size_t)snprintf(out + n, n < size ? size - n : 0, "%s%s", i ? ", " : "", d->choices[i]);
	} else if (d->type == AA_PARAM_BOOL) {
		snprintf(out, size, "true, false");
	} else {
		snprintf(out, size, "%g..%g", d->min, d->max);
	}
}

int cmd_methods(int argc, char **argv)
{
	bool json = want_json(argc, argv);
	json_t *arr = json_array();
	for (int i = 0; i < aa_method_count; i++) {
		const struct aa_method *m = aa_methods[i];
		struct aa_method_params defaults;
		aa_method_defaults(m, &defaults);
		json_t *params = json_array();
		if (!json)
			printf("%s\n    %s (%s)\n", m->name, m->summary, m->seed);
		for (int p = 0; p < m->param_count; p++) {
			const struct aa_param_def *d = &m->params[p];
			char def[64], valid[256];
			aa_method_param_text(m, &defaults, p, def, sizeof def);
			valid_values(d, valid, sizeof valid);
			json_array_append_new(params, json_pack("{ss ss ss ss ss sb}", "name", d->name, "type",
								type_name(d->type), "default", def, "valid", valid,
								"help", d->help ? d->help : "", "main",
								m->main_param && !strcmp(m->main_param, d->name)));
			if (!json)
				printf("    %-18s %-5s default %-8s valid: %s\n        %s%s\n", d->name,
				       type_name(d->type), def, valid, d->help ? d->help : "",
				       m->main_param && !strcmp(m->main_param, d->name)
				       ? " (main parameter: a bare number sets it, e.g. name:N)" : "");
		}
		json_array_append_new(arr, json_pack("{ss ss ss so}", "name", m->name, "summary", m->summary, "seed",
						     m->seed, "params", params));
	}
	if (json) {
		json_dumpf(arr, stdout, JSON_INDENT(2));
		fputc('\n', stdout);
	}
	json_decref(arr);
	return AA_EXIT_OK;
}
