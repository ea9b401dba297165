/* aalab scenes / aalab methods: what a job can name, with parameters, defaults and valid values. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "client.h"
#include "types/method.h"
#include "scene/scene.h"
#include "methods/methods.h"

/* The arguments of a listing command: --json, and at most max_names names (the first is returned in
 * *first, NULL when none). Anything else is a usage error (exit 2): an unknown option was once ignored,
 * and a name given to `aalab methods` listed every method. */
int aa_list_args(const char *cmd, const char *usage, int argc, char **argv, int max_names, bool *json,
		 int *first)
{
	int names = 0;
	*json = false;
	*first = 0;
	for (int i = 1; i < argc; i++) {
		if (strcmp(argv[i], "--json") == 0) {
			*json = true;
		} else if (argv[i][0] == '-') {
			fprintf(stderr, "aalab %s: unknown option '%s'\nusage: aalab %s\n", cmd, argv[i], usage);
			return AA_EXIT_USAGE;
		} else if (++names > max_names) {
			fprintf(stderr, "aalab %s: unexpected argument '%s'\nusage: aalab %s\n", cmd, argv[i], usage);
			return AA_EXIT_USAGE;
		} else if (!*first) {
			*first = i;
		}
	}
	return AA_EXIT_OK;
}

/* One scene loaded whole: what it draws, the animations of its mesh files and what loading dropped. */
static int describe_scene(const char *name, bool json)
{
	char file[1024];
	struct aa_error err = {0};
	struct aa_scene *s = NULL;
	if (aa_scene_resolve(name, file, sizeof file, &err) || aa_scene_load(file, &s, &err)) {
		aa_print_error("scenes", &err);
		return err.code == AA_ERR_INVALID || err.code == AA_ERR_NOT_FOUND || err.code == AA_ERR_LIMIT
			       ? AA_EXIT_USAGE : AA_EXIT_FAILED;
	}
	json_t *o = json_pack("{ss ss ss sI si si si}", "name", s->name, "file", file, "description", s->description,
			      "triangles", (json_int_t)aa_scene_triangle_count(s), "objects", s->model_count,
			      "materials", s->material_count, "textures", s->texture_count);
	json_t *paths = json_array(), *clips = json_array(), *warnings = json_array(), *files = json_array();
	for (int i = 0; i < s->source_count; i++)
		json_array_append_new(files, json_pack("{ss sI}", "path", s->sources[i].path, "bytes",
						       (json_int_t)s->sources[i].size));
	for (int p = 0; p < s->path_count; p++)
		json_array_append_new(paths, json_string(s->paths[p].name));
	for (int r = 0; r < s->rig_count; r++)
		for (int c = 0; c < s->rigs[r].clip_count; c++)
			json_array_append_new(clips, json_pack("{ss ss sf}", "file", s->rigs[r].source, "clip",
							       s->rigs[r].clips[c].name, "seconds", s->rigs[r].clips[c].duration));
	for (int w = 0; w < s->warning_count; w++)
		json_array_append_new(warnings, json_string(s->warnings[w]));
	json_object_set_new(o, "paths", paths);
	json_object_set_new(o, "animations", clips);
	json_object_set_new(o, "warnings", warnings);
	json_object_set_new(o, "files", files);
	if (json) {
		json_dumpf(o, stdout, JSON_INDENT(2));
		fputc('\n', stdout);
	} else {
		printf("%s (%s)\n", s->name, file);
		if (s->description[0]) /* a scene without one gets no blank line */
			printf("  %s\n", s->description);
		printf("  %llu triangles, %d objects, %d materials, %d textures\n  paths: default, static",
		       (unsigned long long)aa_scene_triangle_count(s), s->model_count, s->material_count, s->texture_count);
		for (int p = 0; p < s->path_count; p++)
			printf(", %s", s->paths[p].name);
		putchar('\n');
		for (int r = 0; r < s->rig_count; r++)
			for (int c = 0; c < s->rigs[r].clip_count; c++)
				printf("  animation '%s' of %s: %.3f s\n", s->rigs[r].clips[c].name, s->rigs[r].source,
				       s->rigs[r].clips[c].duration);
		/* what aalabd's scene cache watches besides the scene file (a change to any reloads it) */
		for (int i = 0; i < s->source_count; i++)
			printf("  reads %s (%lld bytes)\n", s->sources[i].path, (long long)s->sources[i].size);
		for (int w = 0; w < s->warning_count; w++)
			printf("  warning: %s\n", s->warnings[w]);
		if (s->warnings_dropped)
			printf("  ... and %d more warnings\n", s->warnings_dropped);
	}
	json_decref(o);
	aa_scene_free(s);
	return AA_EXIT_OK;
}

/* Lists the scenes from their JSON alone: no mesh or texture is loaded (a folder of large assets would
 * take seconds and hundreds of MB), so triangle counts are left to `aalab scenes NAME`. */
int cmd_scenes(int argc, char **argv)
{
	bool json;
	int name, status = aa_list_args("scenes", AA_SCENES_USAGE, argc, argv, 1, &json, &name);
	if (status)
		return status;
	if (name)
		return describe_scene(argv[name], json);
	char **names;
	int count;
	if (aa_scene_list(&names, &count)) {
		fprintf(stderr, "aalab scenes: cannot list scenes\n");
		return AA_EXIT_FAILED;
	}
	json_t *arr = json_array();
	for (int i = 0; i < count; i++) {
		char file[1024];
		struct aa_error err = {0};
		struct aa_scene_summary sum;
		json_t *o = json_pack("{ss}", "name", names[i]);
		if (aa_scene_resolve(names[i], file, sizeof file, &err) == 0 && aa_scene_summarize(file, &sum, &err) == 0) {
			json_t *paths = json_array();
			for (int p = 0; p < sum.path_count; p++)
				json_array_append_new(paths, json_string(sum.paths[p]));
			json_object_set_new(o, "file", json_string(file));
			json_object_set_new(o, "description", json_string(sum.description));
			json_object_set_new(o, "objects", json_integer(sum.object_count));
			json_object_set_new(o, "paths", paths);
			if (!json) {
				printf("%-16s %4d objects  paths: default, static", names[i], sum.object_count);
				for (int p = 0; p < sum.path_count; p++) /* every path the scene defines */
					printf(", %s", sum.paths[p]);
				putchar('\n');
				if (sum.description[0])
					printf("%16s %s\n", "", sum.description);
			}
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

static bool has_method(json_t *all, const char *name)
{
	size_t k;
	json_t *m;
	json_array_foreach(all, k, m)
		if (strcmp(json_string_value(json_object_get(m, "name")), name) == 0)
			return true;
	return false;
}

static bool named_on_line(int argc, char **argv, const char *name)
{
	for (int i = 1; i < argc; i++)
		if (argv[i][0] != '-' && strcmp(argv[i], name) == 0)
			return true;
	return false;
}

/* Keeps the methods named on the command line, in the registry's order; NULL after saying which name is
 * not a method. */
static json_t *named_methods(json_t *all, int argc, char **argv)
{
	size_t k;
	json_t *m;
	for (int i = 1; i < argc; i++) {
		if (argv[i][0] == '-' || has_method(all, argv[i]))
			continue;
		char mean[96];
		aa_method_suggest(argv[i], mean, sizeof mean);
		fprintf(stderr, "aalab methods: unknown method '%s'%s (methods:", argv[i], mean);
		json_array_foreach(all, k, m)
			fprintf(stderr, "%s %s", k ? "," : "", json_string_value(json_object_get(m, "name")));
		fputs(")\n", stderr);
		return NULL;
	}
	json_t *kept = json_array();
	json_array_foreach(all, k, m)
		if (named_on_line(argc, argv, json_string_value(json_object_get(m, "name"))))
			json_array_append(kept, m);
	return kept;
}

int cmd_methods(int argc, char **argv)
{
	bool json;
	int first, status = aa_list_args("methods", AA_METHODS_USAGE, argc, argv, argc, &json, &first);
	if (status)
		return status;
	json_t *arr = aa_methods_describe();
	if (first) {
		json_t *kept = named_methods(arr, argc, argv);
		json_decref(arr);
		if (!kept)
			return AA_EXIT_USAGE;
		arr = kept;
	}
	if (json) {
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
