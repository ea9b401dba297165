/* The folder of stored references (reference_cache.h). An entry is one file, DIR/KK/KEY.ref (KK: the key's
 * first two hex digits), in the format of docs/reference-cache.md: a header, the recipe, the sums, and a
 * CRC-32 of everything before it. Its modification time is its last use: a hit touches it, and the least
 * recently used go first when the folder is over its size. */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <inttypes.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <zlib.h>

#include "reference/reference_cache.h"
#include "util/file_io.h"
#include "util/sha256.h"

#define MAGIC "AALABREF"
#define FORMAT_VERSION 1
#define HEADER_FIXED 104
#define ENCODING_RAW 0 /* little-endian IEEE floats, plane after plane, row after row */

struct aa_reference_cache {
	char dir[2048];
	uint64_t max_bytes;
	pthread_mutex_t lock;
	struct aa_reference_cache_stats stats;
	bool size_known;          /* bytes_now counts the folder (scanned once, then kept up to date) */
	uint64_t bytes_now;
};

void aa_reference_entry_free(struct aa_reference_entry *e)
{
	for (int i = 0; i < AA_REFERENCE_ENTRY_PLANES; i++) {
		free(e->planes[i]);
		e->planes[i] = NULL;
	}
}

static void put32(uint8_t *p, uint32_t v)
{
	for (int i = 0; i < 4; i++)
		p[i] = (uint8_t)(v >> (8 * i));
}

static void put64(uint8_t *p, uint64_t v)
{
	for (int i = 0; i < 8; i++)
		p[i] = (uint8_t)(v >> (8 * i));
}

static uint32_t get32(const uint8_t *p)
{
	return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static uint64_t get64(const uint8_t *p)
{
	return (uint64_t)get32(p) | (uint64_t)get32(p + 4) << 32;
}

static double get_double(const uint8_t *p)
{
	uint64_t bits = get64(p);
	double d;
	memcpy(&d, &bits, sizeof d);
	return d;
}

static void put_double(uint8_t *p, double d)
{
	uint64_t bits;
	memcpy(&bits, &d, sizeof bits);
	put64(p, bits);
}

/* CRC-32 of a buffer of any length (zlib's takes 32-bit lengths). */
static uint32_t crc_of(uint32_t crc, const uint8_t *p, size_t n)
{
	while (n > 0) {
		const uInt chunk = n > (1u << 30) ? (1u << 30) : (uInt)n;
		crc = (uint32_t)crc32(crc, p, chunk);
		p += chunk;
		n -= chunk;
	}
	return crc;
}

static void entry_path(const struct aa_reference_cache *c, const char *hex, char *out, size_t size)
{
	snprintf(out, size, "%s/%.2s/%s.ref", c->dir, hex, hex);
}

int aa_reference_cache_parse_size(const char *field, const char *text, uint64_t *out, struct aa_error *err)
{
	char *end;
	errno = 0;
	const double v = strtod(text, &end);
	double scale = 1;
	if (end != text && *end && !end[1] && strchr("KMGT", *end)) {
		scale = *end == 'K' ? 0x1p10 : *end == 'M' ? 0x1p20 : *end == 'G' ? 0x1p30 : 0x1p40;
		end++;
	}
	if (errno || end == text || *end || !isfinite(v) || v * scale < (double)AA_REFERENCE_CACHE_MIN_BYTES ||
	    v * scale > 0x1p60)
		return aa_error_set(err, AA_ERR_INVALID, field, "expected a size of at least 1M, in bytes or with K, M, "
				    "G or T (e.g. 4G), got '%s'", text);
	*out = (uint64_t)(v * scale);
	return 0;
}

int aa_reference_cache_open(const char *dir, uint64_t max_bytes, struct aa_reference_cache **out,
			    struct aa_error *err)
{
	*out = NULL;
	if (!dir || !dir[0])
		return aa_error_set(err, AA_ERR_INVALID, "reference-cache", "an empty folder name");
	if (strlen(dir) > 1900)
		return aa_error_set(err, AA_ERR_INVALID, "reference-cache", "the folder name is over 1900 bytes");
	struct aa_error made = {0};
	if (aa_file_make_dirs(dir, &made))
		return aa_error_set(err, AA_ERR_IO, "reference-cache", "%s", made.message);
	if (access(dir, R_OK | W_OK | X_OK) != 0)
		return aa_error_set(err, AA_ERR_IO, "reference-cache", "cannot write into %s: %s", dir, strerror(errno));
	struct aa_reference_cache *c = calloc(1, sizeof *c);
	if (!c)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	snprintf(c->dir, sizeof c->dir, "%s", dir);
	c->max_bytes = max_bytes ? max_bytes : AA_REFERENCE_CACHE_DEFAULT_BYTES;
	pthread_mutex_init(&c->lock, NULL);
	*out = c;
	return 0;
}

const char *aa_reference_cache_dir(const struct aa_reference_cache *c)
{
	return c->dir;
}

uint64_t aa_reference_cache_max_bytes(const struct aa_reference_cache *c)
{
	return c->max_bytes;
}

struct aa_reference_cache_stats aa_reference_cache_stats(struct aa_reference_cache *c)
{
	pthread_mutex_lock(&c->lock);
	struct aa_reference_cache_stats s = c->stats;
	pthread_mutex_unlock(&c->lock);
	return s;
}

static void count(struct aa_reference_cache *c, uint64_t *field, uint64_t n)
{
	pthread_mutex_lock(&c->lock);
	*field += n;
	pthread_mutex_unlock(&c->lock);
}

/* ---------------------------------------------------------------- reading */

static int check_entry(const uint8_t *d, size_t n, const uint8_t key[32], struct aa_reference_entry *e,
		       char *why, size_t why_size)
{
	if (n < HEADER_FIXED + 4 || memcmp(d, MAGIC, 8) != 0) {
		snprintf(why, why_size, n < HEADER_FIXED + 4 ? "truncated (%zu bytes)" : "not an entry (no magic)", n);
		return -1;
	}
	const uint32_t crc = get32(d + n - 4);
	if (crc_of((uint32_t)crc32(0, NULL, 0), d, n - 4) != crc) {
		snprintf(why, why_size, "its CRC-32 does not match its bytes (damaged or truncated)");
		return -1;
	}
	if (get32(d + 8) != FORMAT_VERSION) {
		snprintf(why, why_size, "format version %u, this build reads %d", get32(d + 8), FORMAT_VERSION);
		return -1;
	}
	const uint64_t header = get32(d + 12), payload = get64(d + 88), recipe = get32(d + 96);
	e->width = (int)get32(d + 48);
	e->height = (int)get32(d + 52);
	e->plane_count = (int)get32(d + 56);
	const uint32_t encoding = get32(d + 60);
	const uint64_t pixels = (uint64_t)get32(d + 48) * get32(d + 52);
	if (memcmp(d + 16, key, 32) != 0)
		snprintf(why, why_size, "it holds another key");
	else if (header != HEADER_FIXED + recipe || recipe >= AA_REFERENCE_RECIPE_MAX || header + payload + 4 != n)
		snprintf(why, why_size, "its sizes do not add up to the file's");
	else if (encoding != ENCODING_RAW || e->plane_count < 1 || e->plane_count > AA_REFERENCE_ENTRY_PLANES ||
		 pixels == 0 || pixels > (1ull << 28) || payload != pixels * 16 * (uint64_t)e->plane_count)
		snprintf(why, why_size, "its header is not valid");
	else
		why[0] = 0;
	if (why[0])
		return -1;
	for (int i = 0; i < e->plane_count; i++)
		e->samples[i] = (int)get32(d + 64 + 4 * i);
	e->gpu_ms = get_double(d + 72);
	e->cpu_ms = get_double(d + 80);
	memcpy(e->recipe, d + HEADER_FIXED, recipe);
	e->recipe[recipe] = 0;
	const size_t plane_bytes = (size_t)pixels * 16;
	for (int i = 0; i < e->plane_count; i++) {
		if (!(e->planes[i] = malloc(plane_bytes))) {
			snprintf(why, why_size, "out of memory");
			return -2;
		}
		memcpy(e->planes[i], d + header + i * plane_bytes, plane_bytes); /* little-endian hosts only */
	}
	return 0;
}

int aa_reference_cache_get(struct aa_reference_cache *c, const uint8_t key[32], struct aa_reference_entry *e,
			   char *warning, size_t warning_size)
{
	memset(e, 0, sizeof *e);
	char hex[65], path[2200];
	aa_sha256_digest_hex(key, hex);
	entry_path(c, hex, path, sizeof path);
	uint8_t *data;
	size_t n;
	struct aa_error err = {0};
	if (aa_file_read(path, (size_t)1 << 33, &data, &n, &err)) {
		count(c, &c->stats.misses, 1);
		if (err.code == AA_ERR_NOT_FOUND)
			return 0;
		snprintf(warning, warning_size, "reference cache: entry %.16s: %s; rendering it instead", hex, err.message);
		return -1;
	}
	char why[160];
	const int rc = check_entry(data, n, key, e, why, sizeof why);
	free(data);
	if (rc) {
		aa_reference_entry_free(e);
		count(c, &c->stats.misses, 1);
		if (rc == -2) {
			snprintf(warning, warning_size, "reference cache: entry %.16s: %s", hex, why);
			return -1;
		}
		const bool removed = unlink(path) == 0;
		count(c, &c->stats.discarded, 1);
		snprintf(warning, warning_size, "reference cache: entry %.16s failed its check: %s; %s, rendering it again",
			 hex, why, removed ? "removed" : "could not be removed");
		return -1;
	}
	utimensat(AT_FDCWD, path, NULL, 0); /* its last use: the least recently used go first */
	count(c, &c->stats.hits, 1);
	count(c, &c->stats.bytes_read, n);
	return 1;
}

/* ---------------------------------------------------------------- the folder's entries */

struct entry_file {
	char hex[65];
	uint64_t bytes;
	struct timespec used;
};

/* Every entry in the folder (temp files of writers still at work are not entries). */
static int list_entries(const struct aa_reference_cache *c, struct entry_file **out, int *count_out,
			struct aa_error *err)
{
	*out = NULL;
	*count_out = 0;
	DIR *top = opendir(c->dir);
	if (!top)
		return aa_error_set(err, AA_ERR_IO, "reference-cache", "cannot read %s: %s", c->dir, strerror(errno));
	struct entry_file *list = NULL;
	int n = 0, cap = 0, rc = 0;
	struct dirent *sub;
	while (rc == 0 && (sub = readdir(top))) {
		if (strlen(sub->d_name) != 2 || !strchr("0123456789abcdef", sub->d_name[0]) ||
		    !strchr("0123456789abcdef", sub->d_name[1]))
			continue;
		char path[2200];
		snprintf(path, sizeof path, "%s/%s", c->dir, sub->d_name);
		DIR *d = opendir(path);
		if (!d)
			continue;
		struct dirent *f;
		while ((f = readdir(d))) {
			const size_t len = strlen(f->d_name);
			if (f->d_name[0] == '.') /* a writer's temporary file: removed when its writer died */
				aa_file_remove_stale_temp(path, f->d_name);
			if (len != 68 || strcmp(f->d_name + 64, ".ref") != 0 || f->d_name[0] == '.')
				continue;
			char file[2300];
			snprintf(file, sizeof file, "%s/%s", path, f->d_name);
			struct stat st;
			if (stat(file, &st) != 0)
				continue; /* removed meanwhile */
			if (n == cap) {
				cap = cap ? 2 * cap : 256;
				struct entry_file *grown = realloc(list, (size_t)cap * sizeof *grown);
				if (!grown) {
					rc = aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
					break;
				}
				list = grown;
			}
			memcpy(list[n].hex, f->d_name, 64);
			list[n].hex[64] = 0;
			list[n].bytes = (uint64_t)st.st_size;
			list[n].used = st.st_mtim;
			n++;
		}
		closedir(d);
	}
	closedir(top);
	if (rc) {
		free(list);
		return -1;
	}
	*out = list;
	*count_out = n;
	return 0;
}

static int by_use_newest_first(const void *a, const void *b)
{
	const struct entry_file *x = a, *y = b;
	if (x->used.tv_sec != y->used.tv_sec)
		return x->used.tv_sec < y->used.tv_sec ? 1 : -1;
	if (x->used.tv_nsec != y->used.tv_nsec)
		return x->used.tv_nsec < y->used.tv_nsec ? 1 : -1;
	return strcmp(x->hex, y->hex);
}

int aa_reference_cache_trim(struct aa_reference_cache *c, uint64_t max_bytes, struct aa_error *err)
{
	struct entry_file *list;
	int n;
	if (list_entries(c, &list, &n, err))
		return -1;
	qsort(list, (size_t)n, sizeof *list, by_use_newest_first);
	uint64_t total = 0;
	for (int i = 0; i < n; i++)
		total += list[i].bytes;
	for (int i = n - 1; i >= 0 && total > max_bytes; i--) {
		char path[2200];
		entry_path(c, list[i].hex, path, sizeof path);
		if (unlink(path) == 0 || errno == ENOENT) {
			total -= list[i].bytes;
			count(c, &c->stats.evictions, 1);
		}
	}
	free(list);
	pthread_mutex_lock(&c->lock);
	c->bytes_now = total;
	c->size_known = true;
	pthread_mutex_unlock(&c->lock);
	return 0;
}

int aa_reference_cache_keys(struct aa_reference_cache *c, char (**keys)[65], int *count_out, struct aa_error *err)
{
	struct entry_file *list;
	int n;
	*keys = NULL;
	*count_out = 0;
	if (list_entries(c, &list, &n, err))
		return -1;
	qsort(list, (size_t)n, sizeof *list, by_use_newest_first);
	char (*out)[65] = malloc((size_t)(n > 0 ? n : 1) * sizeof *out);
	if (!out) {
		free(list);
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	}
	for (int i = 0; i < n; i++)
		memcpy(out[i], list[i].hex, 65);
	free(list);
	*keys = out;
	*count_out = n;
	return 0;
}

/* ---------------------------------------------------------------- writing */

int aa_reference_cache_put(struct aa_reference_cache *c, const uint8_t key[32], const struct aa_reference_entry *e,
			   struct aa_error *err)
{
	const size_t recipe = strlen(e->recipe), plane_bytes = (size_t)e->width * e->height * 16;
	if (e->plane_count < 1 || e->plane_count > AA_REFERENCE_ENTRY_PLANES || recipe >= AA_REFERENCE_RECIPE_MAX)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "reference cache: a malformed entry");
	uint8_t header[HEADER_FIXED] = {0};
	memcpy(header, MAGIC, 8);
	put32(header + 8, FORMAT_VERSION);
	put32(header + 12, (uint32_t)(HEADER_FIXED + recipe));
	memcpy(header + 16, key, 32);
	put32(header + 48, (uint32_t)e->width);
	put32(header + 52, (uint32_t)e->height);
	put32(header + 56, (uint32_t)e->plane_count);
	put32(header + 60, ENCODING_RAW);
	for (int i = 0; i < e->plane_count; i++)
		put32(header + 64 + 4 * i, (uint32_t)e->samples[i]);
	put_double(header + 72, e->gpu_ms);
	put_double(header + 80, e->cpu_ms);
	put64(header + 88, (uint64_t)plane_bytes * e->plane_count);
	put32(header + 96, (uint32_t)recipe);
	uint32_t crc = crc_of((uint32_t)crc32(0, NULL, 0), header, sizeof header);
	crc = crc_of(crc, (const uint8_t *)e->recipe, recipe);
	for (int i = 0; i < e->plane_count; i++)
		crc = crc_of(crc, (const uint8_t *)e->planes[i], plane_bytes);
	uint8_t trailer[4];
	put32(trailer, crc);
	struct aa_file_part parts[3 + AA_REFERENCE_ENTRY_PLANES] = {{header, sizeof header}, {e->recipe, recipe}};
	int count_parts = 2;
	for (int i = 0; i < e->plane_count; i++)
		parts[count_parts++] = (struct aa_file_part){e->planes[i], plane_bytes};
	parts[count_parts++] = (struct aa_file_part){trailer, sizeof trailer};
	const uint64_t written = sizeof header + recipe + plane_bytes * e->plane_count + sizeof trailer;
	/* the store never takes the last of a disk that results (and aalabd's job states) are written to:
	 * an entry that would leave under 64 MiB, or 5% of the file system, free is not written */
	struct statvfs fs;
	if (statvfs(c->dir, &fs) == 0) {
		const uint64_t total = (uint64_t)fs.f_blocks * fs.f_frsize, avail = (uint64_t)fs.f_bavail * fs.f_frsize;
		const uint64_t margin = total / 20 > (64ull << 20) ? total / 20 : (64ull << 20);
		if (avail < written + margin)
			return aa_error_set(err, AA_ERR_IO, "", "reference cache: not stored: %s would have under %llu MiB "
					    "free", c->dir, (unsigned long long)(margin >> 20));
	}
	char hex[65], sub[2100], name[80];
	aa_sha256_digest_hex(key, hex);
	snprintf(sub, sizeof sub, "%s/%.2s", c->dir, hex);
	snprintf(name, sizeof name, "%s.ref", hex);
	if (aa_file_make_dirs(sub, err) || aa_file_write_atomic(sub, name, parts, count_parts, err)) {
		aa_error_prefix(err, "reference cache");
		return -1;
	}
	count(c, &c->stats.bytes_written, written);
	pthread_mutex_lock(&c->lock);
	c->bytes_now += written;
	const bool over = !c->size_known || c->bytes_now > c->max_bytes;
	pthread_mutex_unlock(&c->lock);
	/* the folder is scanned at the first write, and again only when it may be over (other processes write
	 * to it too); it is trimmed to 90% so that the next few entries do not each scan it again */
	if (over && aa_reference_cache_trim(c, c->max_bytes / 10 * 9, err))
		return -1;
	return 0;
}

/* ---------------------------------------------------------------- totals */

static const char *const stat_names[] = {"hits", "misses", "bytes_read", "bytes_written", "evictions", "discarded"};
#define STAT_COUNT 6

static uint64_t *stat_field(struct aa_reference_cache_stats *s, int i)
{
	uint64_t *f[STAT_COUNT] = {&s->hits, &s->misses, &s->bytes_read, &s->bytes_written, &s->evictions,
				   &s->discarded};
	return f[i];
}

/* The totals file (DIR/stats, "name value" lines), read under the folder's lock. */
static void read_totals(const char *dir, struct aa_reference_cache_stats *s)
{
	char path[2100];
	snprintf(path, sizeof path, "%s/stats", dir);
	FILE *f = fopen(path, "r");
	memset(s, 0, sizeof *s);
	if (!f)
		return;
	char name[32];
	uint64_t v;
	while (fscanf(f, "%31s %" SCNu64, name, &v) == 2)
		for (int i = 0; i < STAT_COUNT; i++)
			if (strcmp(name, stat_names[i]) == 0)
				*stat_field(s, i) = v;
	fclose(f);
}

static int lock_folder(const char *dir)
{
	char path[2100];
	snprintf(path, sizeof path, "%s/lock", dir);
	const int fd = open(path, O_RDWR | O_CREAT | O_CLOEXEC, 0644);
	if (fd >= 0)
		flock(fd, LOCK_EX);
	return fd;
}

static void unlock_folder(int fd)
{
	if (fd >= 0)
		close(fd);
}

void aa_reference_cache_close(struct aa_reference_cache *c)
{
	if (!c)
		return;
	struct aa_reference_cache_stats s = aa_reference_cache_stats(c), total;
	if (s.hits || s.misses || s.evictions || s.discarded) {
		const int fd = lock_folder(c->dir);
		read_totals(c->dir, &total);
		char text[512] = "";
		for (int i = 0; i < STAT_COUNT; i++) {
			size_t len = strlen(text);
			snprintf(text + len, sizeof text - len, "%s %" PRIu64 "\n", stat_names[i],
				 *stat_field(&total, i) + *stat_field(&s, i));
		}
		const struct aa_file_part part = {text, strlen(text)};
		aa_file_write_atomic(c->dir, "stats", &part, 1, NULL); /* the counts are a courtesy: never an error */
		unlock_folder(fd);
	}
	pthread_mutex_destroy(&c->lock);
	free(c);
}

int aa_reference_cache_remove_stale(struct aa_reference_cache *c, struct aa_error *err)
{
	struct entry_file *list;
	int n;
	if (list_entries(c, &list, &n, err)) /* the scan removes them */
		return -1;
	free(list);
	return 0;
}

int aa_reference_cache_usage(struct aa_reference_cache *c, struct aa_reference_cache_usage *u, struct aa_error *err)
{
	memset(u, 0, sizeof *u);
	struct entry_file *list;
	int n;
	if (list_entries(c, &list, &n, err))
		return -1;
	for (int i = 0; i < n; i++)
		u->bytes += list[i].bytes;
	u->entries = (uint64_t)n;
	free(list);
	const int fd = lock_folder(c->dir);
	read_totals(c->dir, &u->total);
	unlock_folder(fd);
	return 0;
}

int aa_reference_cache_clear(struct aa_reference_cache *c, uint64_t *removed, struct aa_error *err)
{
	struct entry_file *list;
	int n;
	*removed = 0;
	if (list_entries(c, &list, &n, err))
		return -1;
	for (int i = 0; i < n; i++) {
		char path[2200];
		entry_path(c, list[i].hex, path, sizeof path);
		*removed += unlink(path) == 0;
	}
	free(list);
	const int fd = lock_folder(c->dir);
	char path[2100];
	snprintf(path, sizeof path, "%s/stats", c->dir);
	unlink(path);
	unlock_folder(fd);
	pthread_mutex_lock(&c->lock);
	c->bytes_now = 0;
	c->size_known = true;
	pthread_mutex_unlock(&c->lock);
	return 0;
}
