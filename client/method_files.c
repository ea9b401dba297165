/* The files of a job's user methods (docs/user-methods.md): read from disk as `aalab run` reads them, kept
 * by name so that they travel to aalabd with the job as one "bundle" payload (docs/protocol.md), and
 * compiled here first, so that a shader that does not compile is refused before it is queued. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "client.h"
#include "methods/user_method.h"

/* A file source that reads the disk and keeps what it read in a JSON object, name -> text. */
static int recording_read(void *ctx, const char *name, char **text, size_t *size, struct aa_error *err)
{
	json_t *files = ctx;
	if (aa_file_source_disk.read(NULL, name, text, size, err))
		return -1;
	/* the daemon keeps method files as JSON strings: text, UTF-8 */
	json_t *s = json_stringn(*text, *size);
	if (!s) {
		free(*text);
		*text = NULL;
		return aa_error_set(err, AA_ERR_INVALID, "", "%s: not UTF-8 text", name);
	}
	json_object_set_new(files, name, s);
	return 0;
}

static bool is_user_method(const json_t *item, const char **list, const char **file)
{
	*list = NULL;
	*file = NULL;
	if (json_is_string(item)) {
		const char *s = json_string_value(item);
		while (*s == ' ' || *s == '\t')
			s++;
		if (strncmp(s, "user", 4) != 0 || (s[4] != ':' && s[4] != '\0'))
			return false;
		*list = s[4] == ':' ? s + 5 : "";
		return true;
	}
	if (json_is_object(item) && json_is_string(json_object_get(item, "name")) &&
	    !strcmp(json_string_value(json_object_get(item, "name")), "user")) {
		*file = json_string_value(json_object_get(json_object_get(item, "params"), "file"));
		return true;
	}
	return false;
}

int aa_job_user_files(const char *cmd, const json_t *job, bool compile, json_t **files)
{
	*files = NULL;
	const json_t *methods = json_object_get(job, "methods"), *item;
	size_t i;
	json_t *read = json_object();
	int rc = 0;
	struct aa_file_source src = {.read = recording_read, .ctx = read};
	json_array_foreach(methods, i, item) {
		const char *list, *file;
		if (!is_user_method(item, &list, &file))
			continue;
		char path[32];
		snprintf(path, sizeof path, "methods[%zu]", i);
		struct aa_error err = {0};
		const struct aa_method *m = NULL;
		struct aa_method_params params;
		struct aa_user_method *um = NULL;
		if (list)
			rc = aa_user_method_parse(list, &src, path, &m, &params, &err);
		else if (file && !(rc = aa_user_method_load(file, &src, path, &um, &err)))
			m = &um->method;
		/* the daemon compiles too; here a shader that does not compile is refused before it is queued
		 * (a missing compiler on this machine leaves the check to the daemon) */
		if (rc == 0 && m && compile && aa_user_method_compile((struct aa_user_method *)aa_user_method_of(m), &err) &&
		    err.code == AA_ERR_INVALID)
			rc = -1;
		aa_method_unref(m);
		if (rc) {
			fprintf(stderr, "aalab %s: %s%s%s\n", cmd, err.path, err.path[0] ? ": " : "", err.message);
			json_decref(read);
			return -1;
		}
	}
	if (json_object_size(read) > 0)
		*files = read;
	else
		json_decref(read);
	return 0;
}

int aa_submit_payload(json_t *files, const char *scene, size_t scene_size, char **payload, size_t *size,
		      const char **format)
{
	*payload = NULL;
	*size = 0;
	*format = NULL;
	if (!files) {
		if (scene) { /* a scene alone goes as before: the bytes of the file */
			*payload = malloc(scene_size ? scene_size : 1);
			if (!*payload)
				return -1;
			memcpy(*payload, scene, scene_size);
			*size = scene_size;
			*format = "scene";
		}
		return 0;
	}
	json_t *bundle = json_pack("{sO}", "files", files);
	if (scene) {
		json_t *text = json_stringn(scene, scene_size);
		if (!text) {
			json_decref(bundle);
			fprintf(stderr, "aalab: the scene file is not UTF-8 text\n");
			return -1;
		}
		json_object_set_new(bundle, "scene", text);
	}
	*payload = json_dumps(bundle, JSON_COMPACT);
	json_decref(bundle);
	if (!*payload)
		return -1;
	*size = strlen(*payload);
	*format = "bundle";
	return 0;
}
