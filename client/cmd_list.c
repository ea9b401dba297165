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

int cmd_methods(int argc, char **argv)
{
	json_t *arr = aa_methods_describe();
	if (want_json(argc, argv)) {
		json_dumpf(arr, stdout, JSON_INDENT(2));
		fputc('\n', stdout);
		json_decref(arr);
		return AA_EXIT_OK;
	}
	size_t i, p;
	json_t *m, *param;
	json_array_foreach(arr, i, m) {
		printf("%s\n    %s (%s)\n", json_string_value(json_object_get(m, "name")),
		       json_string_value(json_object_get(m, "summary")), json_string_value(json_object_get(m, "seed")));
		json_array_foreach(json_object_get(m, "params"), p, param) {
			printf("    %-18s %-5s default %-8s valid: %s\n        %s%s\n",
			       json_string_value(json_object_get(param, "name")),
			       json_string_value(json_object_get(param, "type")),
			       json_string_value(json_object_get(param, "default")),
			       json_string_value(json_object_get(param, "valid")),
			       json_string_value(json_object_get(param, "help")),
			       json_is_true(json_object_get(param, "main"))
				       ? " (main parameter: a bare number sets it, e.g. name:N)" : "");
		}
	}
	json_decref(arr);
	return AA_EXIT_OK;
}
