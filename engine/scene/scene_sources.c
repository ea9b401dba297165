/* The files a scene's load read besides the scene file (meshes, their buffers and material files,
 * textures), each with the size and modification time it had, so that a cache of loaded scenes can tell
 * when one changed (daemon/scene_cache.c): an edited mesh or texture once went unnoticed there, and jobs
 * rendered the old one. The resolvers that turn a scene's or a mesh's file names into paths
 * (sj_resolve_file, aa_resolve_beside) report each path; the load running on this thread collects them. */
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "scene/scene.h"

static _Thread_local struct aa_scene *collecting;

void aa_scene_sources_collect(struct aa_scene *scene)
{
	collecting = scene;
}

static bool same_file(const struct aa_scene_source *src, const struct stat *st)
{
	return src->size == (int64_t)st->st_size && src->mtime.tv_sec == st->st_mtim.tv_sec &&
	       src->mtime.tv_nsec == st->st_mtim.tv_nsec;
}

void aa_scene_source_read(const char *path)
{
	struct aa_scene *s = collecting;
	if (!s)
		return;
	for (int i = 0; i < s->source_count; i++)
		if (strcmp(s->sources[i].path, path) == 0)
			return;
	struct stat st;
	struct aa_scene_source *grown = realloc(s->sources, (size_t)(s->source_count + 1) * sizeof *grown);
	char *copy = grown ? strdup(path) : NULL;
	if (!grown || !copy || stat(path, &st) != 0) {
		if (grown)
			s->sources = grown;
		free(copy);
		s->sources_unknown = true; /* a cache cannot vouch for this scene: it reloads it every time */
		return;
	}
	s->sources = grown;
	s->sources[s->source_count++] = (struct aa_scene_source){
		.path = copy, .size = (int64_t)st.st_size, .mtime = st.st_mtim};
}

bool aa_scene_sources_changed(const struct aa_scene *s)
{
	if (s->sources_unknown)
		return true;
	for (int i = 0; i < s->source_count; i++) {
		struct stat st;
		if (stat(s->sources[i].path, &st) != 0 || !same_file(&s->sources[i], &st))
			return true;
	}
	return false;
}

void aa_scene_sources_free(struct aa_scene *s)
{
	for (int i = 0; i < s->source_count; i++)
		free(s->sources[i].path);
	free(s->sources);
	s->sources = NULL;
	s->source_count = 0;
}
