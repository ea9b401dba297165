/* A scene file's summary for listings (its name, description, paths and object count), read without
 * loading a mesh or texture. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "scene/scene.h"
#include "scene/scene_json.h"
#include "util/file_io.h"

int aa_scene_summarize(const char *path, struct aa_scene_summary *out, struct aa_error *err)
{
	struct stat st;
	json_error_t je;
	memset(out, 0, sizeof *out);
	if (stat(path, &st) != 0 || !S_ISREG(st.st_mode))
		return aa_error_set(err, AA_ERR_NOT_FOUND, "", "scene file '%s' not found", path);
	if ((uint64_t)st.st_size > AA_SCENE_MAX_FILE_BYTES)
		return aa_error_set(err, AA_ERR_LIMIT, "", "%s: scene file is %lld bytes, over the limit of %u", path,
				    (long long)st.st_size, (unsigned)AA_SCENE_MAX_FILE_BYTES);
	uint8_t *text;
	size_t size;
	if (aa_file_read(path, AA_SCENE_MAX_FILE_BYTES, &text, &size, err)) /* never blocks on a FIFO */
		return -1;
	json_t *root = json_loadb((const char *)text, size, JSON_REJECT_DUPLICATES, &je);
	free(text);
	if (!root)
		return sj_parse_error(err, path, &je);
	struct sj s;
	sj_init(&s, path, err);
	char stem[AA_NAME_MAX];
	const char *b = strrchr(path, '/');
	snprintf(stem, sizeof stem, "%s", b ? b + 1 : path);
	if (sj_ends_with(stem, ".json"))
		stem[strlen(stem) - 5] = '\0';
	int rc = sj_expect_object(&s, root) || sj_string(&s, root, "name", stem, out->name, sizeof out->name) ||
		 sj_string(&s, root, "description", "", out->description, sizeof out->description);
	const json_t *paths = json_object_get(root, "paths");
	if (rc == 0 && paths && !json_is_array(paths))
		rc = sj_fail_key(&s, "paths", AA_ERR_INVALID, "expected an array of camera paths");
	for (size_t i = 0; rc == 0 && i < json_array_size(paths) && i < AA_SCENE_MAX_PATHS; i++) {
		char def[16];
		snprintf(def, sizeof def, "path%zu", i);
		size_t mark = sj_push_key(&s, "paths");
		sj_push_index(&s, i);
		rc = sj_expect_object(&s, json_array_get(paths, i)) ||
		     sj_string(&s, json_array_get(paths, i), "name", def, out->paths[i], sizeof out->paths[i]);
		sj_pop(&s, mark);
		out->path_count += rc == 0;
	}
	if (rc == 0 && !paths)
		snprintf(out->paths[out->path_count++], sizeof out->paths[0], "main");
	out->object_count = (int)json_array_size(json_object_get(root, "objects"));
	json_decref(root);
	return rc ? -1 : 0;
}
