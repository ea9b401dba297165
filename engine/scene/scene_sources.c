/* The files a scene's load read besides the scene file (meshes, their buffers and material files,
 * textures), each with the size and modification time it had, so that a cache of loaded scenes can tell
 * when one changed (daemon/scene_cache.c): an edited mesh or texture once went unnoticed there, and jobs
 * rendered the old one. Their bytes, with the scene text's, are the scene's content digest (the key of stored
 * references, engine/reference/reference_key.c). The resolvers that turn a scene's or a mesh's file names into paths
 * (sj_resolve_file, aa_resolve_beside) report each path; the load running on this thread collects them. */
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "scene/scene.h"
#include "util/file_io.h"
#include "util/sha256.h"

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

static void put_u64(struct aa_sha256 *h, uint64_t v)
{
	uint8_t b[8];
	for (int i = 0; i < 8; i++)
		b[i] = (uint8_t)(v >> (8 * i));
	aa_sha256_update(h, b, sizeof b);
}

void aa_scene_sources_digest(struct aa_scene *s, const void *text, size_t size)
{
	struct aa_sha256 h;
	aa_sha256_init(&h);
	aa_sha256_update(&h, "aalab scene content 1", 22);
	put_u64(&h, size);
	aa_sha256_update(&h, text, size);
	put_u64(&h, (uint64_t)s->source_count);
	/* the order is the load's, which the scene text decides: no path is needed, and none is hashed, so
	 * that a copy of the scene in another folder (another node's mount) has the same digest */
	bool known = !s->sources_unknown;
	for (int i = 0; known && i < s->source_count; i++) {
		uint8_t *data;
		size_t n;
		struct stat st;
		if (aa_file_read(s->sources[i].path, SIZE_MAX / 2, &data, &n, NULL)) {
			known = false;
			break;
		}
		uint8_t digest[32];
		aa_sha256(data, n, digest);
		free(data);
		put_u64(&h, n);
		aa_sha256_update(&h, digest, sizeof digest);
		/* read after the load: the bytes are the ones it used only if the file did not change between */
		known = stat(s->sources[i].path, &st) == 0 && same_file(&s->sources[i], &st) && (int64_t)n == st.st_size;
	}
	aa_sha256_final(&h, s->content_sha256);
	s->content_known = known;
}
