/* The worst regions of a job for report.html: the square tiles where the methods differ most from the
 * reference by FLIP, summed over every method and every frame, each with the frame where it is worst.
 * Read back from the FLIP maps beside the report (flip/<method>/NNNN.png store the magma index
 * int(255 v + 0.5) of each pixel's value v, so the value comes back to within 1/510). Each region carries
 * its crops (reference, then every method, as PNG data: URLs of a few hundred bytes), so the page draws
 * them at once, before or without the viewer's frame scripts. */
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "image/image.h"
#include "image/png_io.h"
#include "metrics/flip.h"
#include "results/results.h"

struct magma_entry {
	uint32_t rgb;
	int index;
};

/* The magma colours in index order. */
static void magma_table(struct magma_entry table[256])
{
	float ramp[256];
	uint8_t px[256 * 4];
	struct aa_image_rgba8 img = { .width = 256, .height = 1, .pixels = px };
	for (int i = 0; i < 256; i++)
		ramp[i] = (float)i / 255.0f;
	aa_flip_colorize(ramp, true, &img);
	for (int i = 0; i < 256; i++)
		table[i] = (struct magma_entry){ (uint32_t)px[4 * i] << 16 | (uint32_t)px[4 * i + 1] << 8 | px[4 * i + 2], i };
}

/* The magma index of each colour, hashed (open addressing, linear probing): a lookup for every pixel of
 * every map, so cheaper than a search of a sorted table. Entries colliding on one colour would keep the
 * first index (the 256 colours are distinct). A slot holds rgb | MAGMA_USED, 0 when empty. */
#define MAGMA_SLOTS 1024
#define MAGMA_USED 0x1000000u
struct magma_hash {
	uint32_t key[MAGMA_SLOTS];
	int index[MAGMA_SLOTS];
};

static unsigned magma_slot(uint32_t rgb)
{
	return (rgb * 2654435761u) >> 22; /* the top 10 bits: MAGMA_SLOTS */
}

static void magma_hash_init(struct magma_hash *h, const struct magma_entry table[256])
{
	memset(h->key, 0, sizeof h->key);
	for (int i = 0; i < 256; i++) {
		unsigned s = magma_slot(table[i].rgb);
		while (h->key[s] && h->key[s] != (table[i].rgb | MAGMA_USED))
			s = (s + 1) % MAGMA_SLOTS;
		if (!h->key[s]) {
			h->key[s] = table[i].rgb | MAGMA_USED;
			h->index[s] = table[i].index;
		}
	}
}

/* The colour's magma index, or -1 when it is not a magma colour. */
static int magma_lookup(const struct magma_hash *h, uint32_t rgb)
{
	for (unsigned s = magma_slot(rgb); h->key[s]; s = (s + 1) % MAGMA_SLOTS)
		if (h->key[s] == (rgb | MAGMA_USED))
			return h->index[s];
	return -1;
}

/* Adds each tile's summed FLIP value of one map to sums; -1 when the map cannot be read or is not WxH. */
static int add_map(const char *path, int width, int height, int tile, int tiles_x, const struct magma_hash *table,
		   double *sums)
{
	struct aa_file_pixels px = { 0 };
	struct aa_error err = { 0 };
	if (aa_png_read(path, false, &px, &err) || px.width != width || px.height != height || px.channels < 3) {
		free(px.data);
		return -1;
	}
	const uint8_t *p = px.data;
	for (int y = 0; y < height; y++)
		for (int x = 0; x < width; x++, p += px.channels) {
			const int index = magma_lookup(table, (uint32_t)p[0] << 16 | (uint32_t)p[1] << 8 | p[2]);
			if (index >= 0)
				sums[(y / tile) * tiles_x + x / tile] += index / 255.0;
		}
	free(px.data);
	return 0;
}

/* Frames first + k (k = thread, thread + threads, ... below count): each frame's tile sums, methods in
 * order, into sums + k * tiles (zeroed). */
#define REGION_CHUNK 32
#define REGION_THREADS 4
struct region_sums {
	const struct aa_job_result *r;
	const char *dir;
	int tile, tiles_x, tiles;
	const struct magma_hash *table;
	double *sums;
	int first, count, thread, threads;
	bool ok;
};

static void *region_sums_run(void *arg)
{
	struct region_sums *w = arg;
	const struct aa_job_result *r = w->r;
	for (int k = w->thread; w->ok && k < w->count; k += w->threads)
		for (int m = 0; w->ok && m < r->method_count; m++) {
			char rel[600], path[4096];
			aa_results_frame_relpath("flip", r->methods[m].label, w->first + k, rel, sizeof rel);
			snprintf(path, sizeof path, "%s/%s", w->dir, rel);
			w->ok = add_map(path, r->spec.width, r->spec.height, w->tile, w->tiles_x, w->table,
					w->sums + (size_t)k * w->tiles) == 0;
		}
	return NULL;
}

/* The tile (x, y, w, h) of the PNG at dir/rel as a data: URL, or null when the file cannot be read or is
 * not the job's size. */
static json_t *crop_url(const char *dir, const char *rel, int width, int height, int x, int y, int w, int h)
{
	static const char b64[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
	char path[4096];
	struct aa_file_pixels px = { 0 };
	struct aa_error err = { 0 };
	if ((size_t)snprintf(path, sizeof path, "%s/%s", dir, rel) >= sizeof path ||
	    aa_png_read(path, false, &px, &err) || px.width != width || px.height != height || px.channels < 3) {
		free(px.data);
		return json_null();
	}
	uint8_t tile[4 * 64 * 64];
	struct aa_image_rgba8 img = { .width = w, .height = h, .pixels = tile };
	for (int j = 0; j < h; j++)
		for (int i = 0; i < w; i++) {
			const uint8_t *s = (const uint8_t *)px.data + ((size_t)(y + j) * (size_t)width + (size_t)(x + i)) * (size_t)px.channels;
			uint8_t *d = tile + 4 * (j * w + i);
			d[0] = s[0], d[1] = s[1], d[2] = s[2], d[3] = px.channels == 4 ? s[3] : 255;
		}
	free(px.data);
	uint8_t *png = NULL;
	size_t n = 0;
	if (aa_png_encode(&img, &png, &n, &err))
		return json_null();
	const char prefix[] = "data:image/png;base64,";
	char *url = malloc(sizeof prefix + 4 * (n / 3 + 1));
	if (!url) {
		free(png);
		return json_null();
	}
	char *o = url + sizeof prefix - 1;
	memcpy(url, prefix, sizeof prefix - 1);
	for (size_t i = 0; i < n; i += 3) {
		const unsigned v = (unsigned)png[i] << 16 | (i + 1 < n ? (unsigned)png[i + 1] << 8 : 0) | (i + 2 < n ? png[i + 2] : 0);
		*o++ = b64[v >> 18 & 63];
		*o++ = b64[v >> 12 & 63];
		*o++ = i + 1 < n ? b64[v >> 6 & 63] : '=';
		*o++ = i + 2 < n ? b64[v & 63] : '=';
	}
	*o = '\0';
	free(png);
	json_t *s = json_string(url);
	free(url);
	return s ? s : json_null();
}

json_t *aa_report_worst_regions(const struct aa_job_result *r, const char *dir, int tile, int count)
{
	json_t *out = json_array();
	const int frames = r->method_count > 0 ? r->methods[0].frame_count : 0;
	const int width = r->spec.width, height = r->spec.height;
	if (!r->spec.keep_frames || frames == 0 || width <= 0 || height <= 0 || tile <= 0)
		return out;
	const int tiles_x = (width + tile - 1) / tile, tiles_y = (height + tile - 1) / tile, tiles = tiles_x * tiles_y;
	double *total = calloc((size_t)tiles, sizeof *total), *worst = calloc((size_t)tiles, sizeof *worst);
	int *worst_frame = calloc((size_t)tiles, sizeof *worst_frame);
	struct magma_entry colours[256];
	magma_table(colours);
	struct magma_hash *table = malloc(sizeof *table);
	if (table)
		magma_hash_init(table, colours);
	/* Frames a chunk at a time, their maps read on threads (decoding the PNGs is most of the cost), each
	 * frame's sums made as one thread would make them; then added up in frame order, so the regions are
	 * the same with any number of threads. */
	long cpus = sysconf(_SC_NPROCESSORS_ONLN);
	const int threads = cpus < 1 ? 1 : cpus > REGION_THREADS ? REGION_THREADS : (int)cpus;
	double *chunk = calloc((size_t)REGION_CHUNK * (size_t)tiles, sizeof *chunk);
	bool ok = total && worst && worst_frame && table && chunk;
	for (int f0 = 0; ok && f0 < frames; f0 += REGION_CHUNK) {
		const int n = frames - f0 < REGION_CHUNK ? frames - f0 : REGION_CHUNK;
		memset(chunk, 0, (size_t)n * (size_t)tiles * sizeof *chunk);
		struct region_sums work[REGION_THREADS];
		pthread_t tids[REGION_THREADS];
		bool started[REGION_THREADS] = { false };
		for (int t = 0; t < threads; t++)
			work[t] = (struct region_sums){ .r = r, .dir = dir, .tile = tile, .tiles_x = tiles_x, .tiles = tiles,
							.table = table, .sums = chunk, .first = f0, .count = n,
							.thread = t, .threads = threads, .ok = true };
		for (int t = 1; t < threads; t++)
			started[t] = pthread_create(&tids[t], NULL, region_sums_run, &work[t]) == 0;
		region_sums_run(&work[0]);
		for (int t = 1; t < threads; t++) {
			if (started[t])
				pthread_join(tids[t], NULL);
			else
				region_sums_run(&work[t]);
			ok = ok && work[t].ok;
		}
		ok = ok && work[0].ok;
		for (int k = 0; ok && k < n; k++) {
			const double *in_frame = chunk + (size_t)k * tiles;
			for (int t = 0; t < tiles; t++) {
				total[t] += in_frame[t];
				if (in_frame[t] > worst[t]) {
					worst[t] = in_frame[t];
					worst_frame[t] = f0 + k;
				}
			}
		}
	}
	free(chunk);
	/* The count tiles with the largest totals, worst first (tiles are disjoint: no overlap to resolve). */
	for (int k = 0; ok && k < count; k++) {
		int best = -1;
		for (int t = 0; t < tiles; t++)
			if (total[t] > 0 && (best < 0 || total[t] > total[best]))
				best = t;
		if (best < 0)
			break;
		const int x = (best % tiles_x) * tile, y = (best / tiles_x) * tile;
		const int w = x + tile > width ? width - x : tile, h = y + tile > height ? height - y : tile;
		/* mean FLIP per pixel of the tile over methods and frames */
		const double mean = total[best] / ((double)w * h * r->method_count * frames);
		json_t *crops = json_array();
		char rel[600];
		aa_results_frame_relpath("frames", "reference", worst_frame[best], rel, sizeof rel);
		json_array_append_new(crops, w <= 64 && h <= 64 ? crop_url(dir, rel, width, height, x, y, w, h) : json_null());
		for (int m = 0; m < r->method_count; m++) {
			aa_results_frame_relpath("frames", r->methods[m].label, worst_frame[best], rel, sizeof rel);
			json_array_append_new(crops, w <= 64 && h <= 64 ? crop_url(dir, rel, width, height, x, y, w, h) : json_null());
		}
		json_array_append_new(out, json_pack("{si si si si si sf so}", "x", x, "y", y, "w", w, "h", h, "ordinal",
						     worst_frame[best], "flip_mean", mean, "crops", crops));
		total[best] = 0;
	}
	if (!ok)
		json_array_clear(out);
	free(total);
	free(worst);
	free(worst_frame);
	free(table);
	return out;
}
