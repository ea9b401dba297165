/* The scene cache: scenes loaded by the GPU worker, kept within a byte budget (aa_scene_bytes), the least
 * recently used dropped first. An entry is reloaded when the size or modification time of its file, or of
 * any file its load read (meshes, their buffers, textures: aa_scene_sources_changed), changed. */
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "jobs.h"

struct entry {
	char file[1024];
	struct timespec mtime;
	off_t size;
	struct aa_scene *scene;
	uint64_t bytes;
	struct entry *prev, *next; /* most recently used first */
};

struct scene_cache {
	pthread_mutex_t lock;      /* only for the counters and budget read by /metrics */
	struct entry *head, *tail;
	uint64_t budget, bytes;
	uint64_t hits, misses, reloads, evictions;
	int entries;
};

struct scene_cache *scene_cache_create(uint64_t budget_bytes)
{
	struct scene_cache *c = calloc(1, sizeof *c);
	if (!c)
		return NULL;
	pthread_mutex_init(&c->lock, NULL);
	c->budget = budget_bytes;
	return c;
}

static void unlink_entry(struct scene_cache *c, struct entry *e)
{
	if (e->prev)
		e->prev->next = e->next;
	else
		c->head = e->next;
	if (e->next)
		e->next->prev = e->prev;
	else
		c->tail = e->prev;
	e->prev = e->next = NULL;
}

static void push_front(struct scene_cache *c, struct entry *e)
{
	e->prev = NULL;
	e->next = c->head;
	if (c->head)
		c->head->prev = e;
	c->head = e;
	if (!c->tail)
		c->tail = e;
}

static void drop(struct scene_cache *c, struct entry *e)
{
	unlink_entry(c, e);
	c->bytes -= e->bytes;
	c->entries--;
	aa_scene_free(e->scene);
	free(e);
}

void scene_cache_destroy(struct scene_cache *c)
{
	if (!c)
		return;
	while (c->head)
		drop(c, c->head);
	pthread_mutex_destroy(&c->lock);
	free(c);
}

/* Keeps the head (the scene in use) even when it alone is over the budget. */
static void evict(struct scene_cache *c)
{
	while (c->bytes > c->budget && c->tail && c->tail != c->head) {
		drop(c, c->tail);
		c->evictions++;
	}
}

void scene_cache_set_budget(struct scene_cache *c, uint64_t budget_bytes)
{
	pthread_mutex_lock(&c->lock);
	c->budget = budget_bytes; /* applied at the next lookup, in the worker thread that owns the entries */
	pthread_mutex_unlock(&c->lock);
}

const struct aa_scene *scene_cache_get(struct scene_cache *c, const char *file, const char *shown,
				      struct aa_error *err)
{
	struct stat st;
	if (stat(file, &st) < 0) {
		aa_error_set(err, AA_ERR_NOT_FOUND, "scene", "cannot read scene file %s", shown);
		return NULL;
	}
	pthread_mutex_lock(&c->lock);
	struct entry *e = c->head;
	while (e && strcmp(e->file, file) != 0)
		e = e->next;
	if (e && e->size == st.st_size && e->mtime.tv_sec == st.st_mtim.tv_sec &&
	    e->mtime.tv_nsec == st.st_mtim.tv_nsec && !aa_scene_sources_changed(e->scene)) {
		c->hits++;
		unlink_entry(c, e);
		push_front(c, e);
		evict(c);
		pthread_mutex_unlock(&c->lock);
		return e->scene;
	}
	if (e) {
		drop(c, e); /* changed on disk: load it again */
		c->reloads++;
	}
	c->misses++;
	pthread_mutex_unlock(&c->lock);

	struct aa_scene *scene;
	if (aa_scene_load_as(file, shown, &scene, err))
		return NULL;
	e = calloc(1, sizeof *e);
	if (!e) {
		aa_scene_free(scene);
		aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
		return NULL;
	}
	snprintf(e->file, sizeof e->file, "%s", file);
	e->mtime = st.st_mtim;
	e->size = st.st_size;
	e->scene = scene;
	e->bytes = aa_scene_bytes(scene) + sizeof *scene;
	pthread_mutex_lock(&c->lock);
	push_front(c, e);
	c->bytes += e->bytes;
	c->entries++;
	evict(c);
	pthread_mutex_unlock(&c->lock);
	return scene;
}

void scene_cache_stats(struct scene_cache *c, struct scene_cache_stats *out)
{
	pthread_mutex_lock(&c->lock);
	*out = (struct scene_cache_stats){c->hits, c->misses, c->reloads, c->evictions, c->bytes, c->budget,
					  c->entries};
	pthread_mutex_unlock(&c->lock);
}
