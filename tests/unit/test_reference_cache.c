/* The store of references without a GPU: an entry read back as written; a truncated, bit-flipped or
 * misplaced entry is found, removed and reported; two processes writing one key at once both succeed
 * and leave one whole entry; past its size the store removes the least recently used entries first; a dead
 * writer's temporary file is removed, a live one's kept. */
#include <fcntl.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmocka.h>

#include "reference/reference_cache.h"
#include "util/sha256.h"

static char dir[256];

static int setup(void **state)
{
	(void)state;
	snprintf(dir, sizeof dir, "/tmp/aalab-test-refcache-XXXXXX");
	return mkdtemp(dir) ? 0 : -1;
}

static int teardown(void **state)
{
	(void)state;
	char cmd[300];
	snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
	return system(cmd);
}

static void make_key(int i, uint8_t key[32])
{
	char text[32];
	snprintf(text, sizeof text, "key %d", i);
	aa_sha256(text, strlen(text), key);
}

/* An entry of w x h with two planes whose values depend on seed. */
static void make_entry(struct aa_reference_entry *e, int w, int h, int seed)
{
	memset(e, 0, sizeof *e);
	e->width = w;
	e->height = h;
	e->plane_count = 2;
	e->samples[0] = 32;
	e->samples[1] = 64;
	e->gpu_ms = 12.5;
	e->cpu_ms = 13.25;
	snprintf(e->recipe, sizeof e->recipe, "{\"scene\":\"x.json\",\"frame\":%d}", seed);
	for (int p = 0; p < 2; p++) {
		e->planes[p] = malloc((size_t)w * h * 16);
		for (int i = 0; i < w * h * 4; i++)
			e->planes[p][i] = (float)(i * (p + 1) + seed) / 7.0f;
	}
}

static void path_of(const uint8_t key[32], char *out, size_t size)
{
	char hex[65];
	aa_sha256_digest_hex(key, hex);
	snprintf(out, size, "%s/%.2s/%s.ref", dir, hex, hex);
}

static void round_trip(void **state)
{
	(void)state;
	struct aa_reference_cache *c;
	struct aa_error err = {0};
	assert_int_equal(aa_reference_cache_open(dir, 0, &c, &err), 0);
	uint8_t key[32];
	make_key(1, key);
	struct aa_reference_entry in, out;
	char warning[256] = "";
	assert_int_equal(aa_reference_cache_get(c, key, &out, warning, sizeof warning), 0);
	make_entry(&in, 5, 3, 1);
	assert_int_equal(aa_reference_cache_put(c, key, &in, &err), 0);
	assert_int_equal(aa_reference_cache_get(c, key, &out, warning, sizeof warning), 1);
	assert_int_equal(out.width, 5);
	assert_int_equal(out.height, 3);
	assert_int_equal(out.plane_count, 2);
	assert_int_equal(out.samples[0], 32);
	assert_int_equal(out.samples[1], 64);
	assert_true(out.gpu_ms == 12.5 && out.cpu_ms == 13.25);
	assert_string_equal(out.recipe, in.recipe);
	for (int p = 0; p < 2; p++)
		assert_memory_equal(out.planes[p], in.planes[p], 5 * 3 * 16);
	struct aa_reference_cache_stats s = aa_reference_cache_stats(c);
	assert_int_equal(s.hits, 1);
	assert_int_equal(s.misses, 1);
	aa_reference_entry_free(&in);
	aa_reference_entry_free(&out);
	aa_reference_cache_close(c);
	/* the counts of every process are kept in the folder */
	assert_int_equal(aa_reference_cache_open(dir, 0, &c, &err), 0);
	struct aa_reference_cache_usage u;
	assert_int_equal(aa_reference_cache_usage(c, &u, &err), 0);
	assert_int_equal(u.entries, 1);
	assert_int_equal(u.total.hits, 1);
	assert_int_equal(u.total.misses, 1);
	aa_reference_cache_close(c);
}

/* damage: 0 truncated by one byte, 1 a bit flipped in the sums, 2 another key's entry under this name */
static void damaged(void **state)
{
	(void)state;
	for (int kind = 0; kind < 3; kind++) {
		struct aa_reference_cache *c;
		struct aa_error err = {0};
		assert_int_equal(aa_reference_cache_open(dir, 0, &c, &err), 0);
		uint8_t key[32], other[32];
		make_key(100 + kind, key);
		make_key(200 + kind, other);
		struct aa_reference_entry in, out;
		make_entry(&in, 8, 4, kind);
		assert_int_equal(aa_reference_cache_put(c, kind == 2 ? other : key, &in, &err), 0);
		char path[512], from[512];
		path_of(key, path, sizeof path);
		if (kind == 2) {
			path_of(other, from, sizeof from);
			char sub[512];
			snprintf(sub, sizeof sub, "%s", path);
			*strrchr(sub, '/') = 0;
			mkdir(sub, 0755);
			assert_int_equal(rename(from, path), 0);
		} else {
			struct stat st;
			assert_int_equal(stat(path, &st), 0);
			if (kind == 0) {
				assert_int_equal(truncate(path, st.st_size - 1), 0);
			} else {
				int fd = open(path, O_RDWR);
				unsigned char b;
				assert_int_equal(pread(fd, &b, 1, st.st_size - 100), 1);
				b ^= 0x10;
				assert_int_equal(pwrite(fd, &b, 1, st.st_size - 100), 1);
				close(fd);
			}
		}
		char warning[256] = "";
		assert_int_equal(aa_reference_cache_get(c, key, &out, warning, sizeof warning), -1);
		assert_non_null(strstr(warning, "removed"));
		assert_int_equal(access(path, F_OK), -1); /* gone: never used again */
		assert_int_equal(aa_reference_cache_get(c, key, &out, warning, sizeof warning), 0);
		assert_int_equal(aa_reference_cache_stats(c).discarded, 1);
		aa_reference_entry_free(&in);
		aa_reference_cache_close(c);
	}
}

/* Two processes write the same key 30 times each, at once: every write succeeds, and one whole entry
 * (and no temporary file) is left. */
static void concurrent_writers(void **state)
{
	(void)state;
	uint8_t key[32];
	make_key(7, key);
	pid_t pids[2];
	for (int p = 0; p < 2; p++) {
		pids[p] = fork();
		assert_true(pids[p] >= 0);
		if (pids[p] == 0) {
			struct aa_reference_cache *c;
			struct aa_error err = {0};
			if (aa_reference_cache_open(dir, 0, &c, &err))
				_exit(2);
			struct aa_reference_entry e;
			make_entry(&e, 64, 64, 7);
			int failed = 0;
			for (int i = 0; i < 30; i++)
				failed += aa_reference_cache_put(c, key, &e, &err) != 0;
			aa_reference_entry_free(&e);
			aa_reference_cache_close(c);
			_exit(failed ? 1 : 0);
		}
	}
	for (int p = 0; p < 2; p++) {
		int status;
		assert_int_equal(waitpid(pids[p], &status, 0), pids[p]);
		assert_true(WIFEXITED(status));
		assert_int_equal(WEXITSTATUS(status), 0);
	}
	struct aa_reference_cache *c;
	struct aa_error err = {0};
	assert_int_equal(aa_reference_cache_open(dir, 0, &c, &err), 0);
	struct aa_reference_entry in, out;
	make_entry(&in, 64, 64, 7);
	char warning[256] = "";
	assert_int_equal(aa_reference_cache_get(c, key, &out, warning, sizeof warning), 1);
	assert_memory_equal(out.planes[1], in.planes[1], 64 * 64 * 16);
	char path[512], cmd[700];
	path_of(key, path, sizeof path);
	*strrchr(path, '/') = 0;
	snprintf(cmd, sizeof cmd, "test $(ls -A '%s' | wc -l) -eq 1", path);
	assert_int_equal(system(cmd), 0);
	aa_reference_entry_free(&in);
	aa_reference_entry_free(&out);
	aa_reference_cache_close(c);
}

/* Entries of 256 KiB in a store of 1 MiB: the least recently used (oldest time, a read refreshes it) go
 * first, and the store stays under its size. */
static void least_recently_used_out(void **state)
{
	(void)state;
	char sub[300];
	snprintf(sub, sizeof sub, "%s/lru", dir);
	struct aa_reference_cache *c;
	struct aa_error err = {0};
	assert_int_equal(aa_reference_cache_open(sub, 1 << 20, &c, &err), 0);
	uint8_t keys[6][32];
	struct aa_reference_entry e, out;
	make_entry(&e, 64, 64, 0);
	e.plane_count = 1; /* 64 KiB; four make 256 KiB */
	struct aa_reference_entry big = e;
	big.width = 128;
	big.height = 128;
	big.planes[0] = calloc(128 * 128 * 4, sizeof(float));
	char warning[256];
	for (int i = 0; i < 3; i++) {
		make_key(300 + i, keys[i]);
		assert_int_equal(aa_reference_cache_put(c, keys[i], &big, &err), 0);
		char path[512];
		snprintf(path, sizeof path, "%s", sub);
		char hex[65];
		aa_sha256_digest_hex(keys[i], hex);
		snprintf(path, sizeof path, "%s/%.2s/%s.ref", sub, hex, hex);
		struct timespec t[2] = {{1000000 + i * 10, 0}, {1000000 + i * 10, 0}};
		assert_int_equal(utimensat(AT_FDCWD, path, t, 0), 0);
	}
	/* entry 0 is read: now the most recently used; 1 is the oldest */
	assert_int_equal(aa_reference_cache_get(c, keys[0], &out, warning, sizeof warning), 1);
	aa_reference_entry_free(&out);
	for (int i = 3; i < 6; i++) {
		make_key(300 + i, keys[i]);
		assert_int_equal(aa_reference_cache_put(c, keys[i], &big, &err), 0);
	}
	struct aa_reference_cache_usage u;
	assert_int_equal(aa_reference_cache_usage(c, &u, &err), 0);
	assert_true(u.bytes <= (1 << 20));
	assert_true(aa_reference_cache_stats(c).evictions >= 2);
	/* the newest three and the one read survive in that order of preference; 1 and 2 went first */
	assert_int_equal(aa_reference_cache_get(c, keys[1], &out, warning, sizeof warning), 0);
	assert_int_equal(aa_reference_cache_get(c, keys[2], &out, warning, sizeof warning), 0);
	assert_int_equal(aa_reference_cache_get(c, keys[5], &out, warning, sizeof warning), 1);
	aa_reference_entry_free(&out);
	free(big.planes[0]);
	e.plane_count = 2;
	aa_reference_entry_free(&e);
	aa_reference_cache_close(c);
}

/* A writer that died leaves its temporary file: the next scan of the folder removes it; a live writer's
 * (it holds the file's lock) and other hidden files stay. */
static void stale_temporaries(void **state)
{
	(void)state;
	char sub[300];
	snprintf(sub, sizeof sub, "%s/temps", dir);
	struct aa_reference_cache *c;
	struct aa_error err = {0};
	assert_int_equal(aa_reference_cache_open(sub, 0, &c, &err), 0);
	uint8_t key[32];
	make_key(400, key);
	struct aa_reference_entry e;
	make_entry(&e, 8, 8, 4);
	assert_int_equal(aa_reference_cache_put(c, key, &e, &err), 0);
	char hex[65], dead[600], live[600], other[600];
	aa_sha256_digest_hex(key, hex);
	snprintf(dead, sizeof dead, "%s/%.2s/.%s.ref.Dead01", sub, hex, hex);
	snprintf(live, sizeof live, "%s/%.2s/.%s.ref.Live01", sub, hex, hex);
	snprintf(other, sizeof other, "%s/%.2s/.keep", sub, hex);
	const int dead_fd = open(dead, O_CREAT | O_WRONLY, 0600), live_fd = open(live, O_CREAT | O_WRONLY, 0600);
	const int other_fd = open(other, O_CREAT | O_WRONLY, 0600);
	assert_true(dead_fd >= 0 && live_fd >= 0 && other_fd >= 0);
	close(dead_fd); /* its writer is gone: no lock */
	close(other_fd);
	assert_int_equal(flock(live_fd, LOCK_EX), 0);
	struct aa_reference_cache_usage u;
	assert_int_equal(aa_reference_cache_usage(c, &u, &err), 0);
	assert_int_equal(u.entries, 1);
	assert_int_equal(access(dead, F_OK), -1);
	assert_int_equal(access(live, F_OK), 0);
	assert_int_equal(access(other, F_OK), 0);
	close(live_fd); /* now its writer is gone too */
	assert_int_equal(aa_reference_cache_usage(c, &u, &err), 0);
	assert_int_equal(access(live, F_OK), -1);
	aa_reference_entry_free(&e);
	aa_reference_cache_close(c);
}

static void settings(void **state)
{
	(void)state;
	uint64_t v;
	struct aa_error err = {0};
	assert_int_equal(aa_reference_cache_parse_size("reference-cache-size", "4G", &v, &err), 0);
	assert_int_equal(v, 4ull << 30);
	assert_int_equal(aa_reference_cache_parse_size("reference-cache-size", "1048576", &v, &err), 0);
	assert_int_equal(aa_reference_cache_parse_size("reference-cache-size", "12k", &v, &err), -1);
	assert_string_equal(err.path, "reference-cache-size");
	assert_int_equal(aa_reference_cache_parse_size("reference-cache-size", "100K", &v, &err), -1);
	assert_int_equal(aa_reference_cache_parse_size("reference-cache-size", "", &v, &err), -1);
	struct aa_reference_cache *c;
	assert_int_equal(aa_reference_cache_open("/proc/aalab-no", 0, &c, &err), -1);
	assert_string_equal(err.path, "reference-cache");
	assert_non_null(strstr(err.message, "/proc/aalab-no"));
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(round_trip),
		cmocka_unit_test(damaged),
		cmocka_unit_test(concurrent_writers),
		cmocka_unit_test(least_recently_used_out),
		cmocka_unit_test(stale_temporaries),
		cmocka_unit_test(settings),
	};
	return cmocka_run_group_tests(tests, setup, teardown);
}
