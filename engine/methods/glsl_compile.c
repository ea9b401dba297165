/* Runs glslangValidator on a user's shader in a temporary folder and keeps the SPIR-V by content hash. */
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "util/sha256.h"
#include "methods/glsl_compile.h"

#ifndef AA_GLSLANG
#define AA_GLSLANG "glslangValidator"
#endif

/* A compile that runs longer than this is stopped (a preprocessor loop in a user's shader). */
#define COMPILE_SECONDS 60
#define OUTPUT_MAX (64 * 1024)

extern char **environ;

static char cache_override[1024];
static int cache_override_set; /* 0: default, 1: cache_override ("" = off) */

void aa_glsl_set_cache_dir(const char *dir)
{
	cache_override_set = dir != NULL;
	snprintf(cache_override, sizeof cache_override, "%s", dir ? dir : "");
}

void aa_glsl_cache_dir(char *out, size_t size)
{
	const char *env = getenv("AALAB_CACHE_DIR"), *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
	if (cache_override_set)
		snprintf(out, size, "%s%s", cache_override, cache_override[0] ? "/spirv" : "");
	else if (env && *env)
		snprintf(out, size, "%s/spirv", env);
	else if (xdg && *xdg)
		snprintf(out, size, "%s/aalab/spirv", xdg);
	else if (home && *home)
		snprintf(out, size, "%s/.cache/aalab/spirv", home);
	else
		snprintf(out, size, "%s", "");
}

static const char *compiler(void)
{
	const char *env = getenv("AALAB_GLSLANG");
	return env && *env ? env : AA_GLSLANG;
}

static double now_ms(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

/* Runs argv with stdout and stderr into *output (NUL-terminated, at most OUTPUT_MAX bytes kept); stops it
 * at the time limit. Returns its exit status, -1 if it could not run, -2 if it was stopped. */
static int run(char *const argv[], char **output, struct aa_error *err)
{
	*output = NULL;
	int fds[2];
	if (pipe2(fds, O_CLOEXEC) != 0)
		return aa_error_set(err, AA_ERR_IO, "", "cannot make a pipe for %s: %s", argv[0], strerror(errno)), -1;
	posix_spawn_file_actions_t fa;
	posix_spawn_file_actions_init(&fa);
	posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
	posix_spawn_file_actions_adddup2(&fa, fds[1], 1);
	posix_spawn_file_actions_adddup2(&fa, fds[1], 2);
	pid_t pid;
	int rc = posix_spawnp(&pid, argv[0], &fa, NULL, argv, environ);
	posix_spawn_file_actions_destroy(&fa);
	close(fds[1]);
	if (rc != 0) {
		close(fds[0]);
		aa_error_set(err, AA_ERR_INTERNAL, "", "cannot run %s (%s): user methods compile GLSL with it; install "
			     "glslang-tools or set $AALAB_GLSLANG", argv[0], strerror(rc));
		return -1;
	}
	char *buf = malloc(OUTPUT_MAX + 1);
	size_t used = 0;
	bool stopped = false;
	const double deadline = now_ms() + COMPILE_SECONDS * 1000.0;
	for (;;) {
		double left = deadline - now_ms();
		if (left <= 0) {
			stopped = true;
			break;
		}
		struct pollfd p = {fds[0], POLLIN, 0};
		int n = poll(&p, 1, (int)left + 1);
		if (n < 0 && errno == EINTR)
			continue;
		if (n <= 0)
			continue;
		char chunk[4096];
		ssize_t got = read(fds[0], chunk, sizeof chunk);
		if (got < 0 && errno == EINTR)
			continue;
		if (got <= 0)
			break;
		size_t take = buf && used + (size_t)got <= OUTPUT_MAX ? (size_t)got : buf ? OUTPUT_MAX - used : 0;
		if (take)
			memcpy(buf + used, chunk, take);
		used += take;
	}
	close(fds[0]);
	if (stopped)
		kill(pid, SIGKILL);
	int status = 0;
	while (waitpid(pid, &status, 0) < 0 && errno == EINTR)
		;
	if (buf)
		buf[used] = '\0';
	*output = buf;
	if (stopped)
		return -2;
	return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

/* The compiler's version output, part of every cache key: another glslang may compile differently. */
static const char *compiler_version(struct aa_error *err)
{
	static char version[512];
	static char which[1024];
	if (version[0] && !strcmp(which, compiler()))
		return version;
	char *argv[] = {(char *)compiler(), "--version", NULL};
	char *out = NULL;
	int rc = run(argv, &out, err);
	if (rc != 0) {
		if (rc > 0 || rc == -2)
			aa_error_set(err, AA_ERR_INTERNAL, "", "%s --version failed (status %d): user methods compile GLSL "
				     "with glslangValidator (glslang-tools)", compiler(), rc);
		free(out);
		return NULL;
	}
	snprintf(version, sizeof version, "%s", out ? out : "");
	snprintf(which, sizeof which, "%s", compiler());
	free(out);
	return version;
}

static bool spirv_valid(const void *data, size_t size)
{
	uint32_t magic;
	if (size < 20 || size % 4 != 0)
		return false;
	memcpy(&magic, data, 4);
	return magic == 0x07230203u;
}

static int read_file(const char *path, uint32_t **words, size_t *bytes)
{
	FILE *f = fopen(path, "rb");
	if (!f)
		return -1;
	struct stat st;
	void *data = NULL;
	int rc = -1;
	if (fstat(fileno(f), &st) == 0 && st.st_size > 0 && st.st_size < (64 << 20) &&
	    (data = malloc((size_t)st.st_size)) && fread(data, 1, (size_t)st.st_size, f) == (size_t)st.st_size &&
	    spirv_valid(data, (size_t)st.st_size)) {
		*words = data;
		*bytes = (size_t)st.st_size;
		data = NULL;
		rc = 0;
	}
	free(data);
	fclose(f);
	return rc;
}

static int mkdir_p(const char *dir)
{
	char tmp[1024];
	snprintf(tmp, sizeof tmp, "%s", dir);
	for (char *p = tmp + 1; *p; p++)
		if (*p == '/') {
			*p = '\0';
			if (mkdir(tmp, 0755) != 0 && errno != EEXIST)
				return -1;
			*p = '/';
		}
	return mkdir(tmp, 0755) != 0 && errno != EEXIST ? -1 : 0;
}

/* Written beside its final name and renamed, so that a reader never sees half a file. Failing to cache
 * costs only a compile next time, so failures are silent. */
static void cache_store(const char *dir, const char *path, const uint32_t *words, size_t bytes)
{
	if (mkdir_p(dir) != 0)
		return;
	char tmp[1200];
	snprintf(tmp, sizeof tmp, "%s/.tmp.%ld.XXXXXX", dir, (long)getpid());
	int fd = mkstemp(tmp);
	if (fd < 0)
		return;
	bool ok = write(fd, words, bytes) == (ssize_t)bytes;
	ok &= close(fd) == 0;
	if (!ok || rename(tmp, path) != 0)
		unlink(tmp);
}

/* Rewrites glslangValidator's "ERROR: TMP/pass.frag:12: message" lines as "FILE:12: message", up to three
 * of them, skipping its summary lines. */
static void compile_message(const char *output, const char *tmp_file, const char *shown_name, char *out,
			    size_t size)
{
	int shown = 0, more = 0;
	out[0] = '\0';
	const size_t tmp_len = strlen(tmp_file);
	for (const char *p = output; p && *p;) {
		const char *end = strchr(p, '\n');
		size_t n = end ? (size_t)(end - p) : strlen(p);
		char line[1024];
		snprintf(line, sizeof line, "%.*s", (int)(n < sizeof line ? n : sizeof line - 1), p);
		p = end ? end + 1 : p + n;
		while (strlen(line) && (line[strlen(line) - 1] == ' ' || line[strlen(line) - 1] == '\r'))
			line[strlen(line) - 1] = '\0';
		const char *text = line;
		if (!strncmp(text, "ERROR: ", 7))
			text += 7;
		else
			continue;
		if (strstr(text, "compilation terminated") || strstr(text, "compilation errors") ||
		    strstr(text, "No code generated"))
			continue;
		if (shown == 3) {
			more++;
			continue;
		}
		char rewritten[1100];
		if (!strncmp(text, tmp_file, tmp_len))
			snprintf(rewritten, sizeof rewritten, "%s%s", shown_name, text + tmp_len);
		else
			snprintf(rewritten, sizeof rewritten, "%s: %s", shown_name, text);
		size_t used = strlen(out);
		snprintf(out + used, size - used, "%s%.*s", shown ? "; " : "", (int)(size - used), rewritten);
		shown++;
	}
	if (more) {
		size_t used = strlen(out);
		snprintf(out + used, size - used, " (and %d more)", more);
	}
	if (!shown) /* no ERROR line: say what the compiler said */
		snprintf(out, size, "%s: %.600s", shown_name, output ? output : "");
}

int aa_glsl_compile(const char *glsl, size_t size, bool compute, const char *shown_name, uint32_t **words,
		    size_t *bytes, bool *cached, struct aa_error *err)
{
	*words = NULL;
	*bytes = 0;
	*cached = false;
	const char *version = compiler_version(err);
	if (!version)
		return -1;
	const char *stage = compute ? "comp" : "frag";
	struct aa_sha256 h;
	uint8_t digest[32];
	char hex[65], dir[1024], path[1200];
	aa_sha256_init(&h);
	aa_sha256_update(&h, "aalab-glsl-1\n", 13);
	aa_sha256_update(&h, version, strlen(version) + 1);
	aa_sha256_update(&h, stage, 5);
	aa_sha256_update(&h, glsl, size);
	aa_sha256_final(&h, digest);
	aa_sha256_digest_hex(digest, hex);
	aa_glsl_cache_dir(dir, sizeof dir);
	if (dir[0]) {
		snprintf(path, sizeof path, "%s/%s.spv", dir, hex);
		if (read_file(path, words, bytes) == 0) {
			*cached = true;
			return 0;
		}
	}

	const char *tmpdir = getenv("TMPDIR");
	char work[1024], src[1100], spv[1100];
	snprintf(work, sizeof work, "%s/aalab-glsl.XXXXXX", tmpdir && *tmpdir ? tmpdir : "/tmp");
	if (!mkdtemp(work))
		return aa_error_set(err, AA_ERR_IO, "", "cannot make a folder to compile %s in: %s", shown_name,
				    strerror(errno));
	snprintf(src, sizeof src, "%s/pass.%s", work, stage);
	snprintf(spv, sizeof spv, "%s/pass.spv", work);
	FILE *f = fopen(src, "wb");
	bool wrote = f && fwrite(glsl, 1, size, f) == size;
	if (f)
		wrote &= fclose(f) == 0;
	int rc = -1;
	char *output = NULL;
	if (!wrote) {
		aa_error_set(err, AA_ERR_IO, "", "cannot write %s to compile %s", src, shown_name);
		goto out;
	}
	char *argv[] = {(char *)compiler(), "-V", "--target-env", "vulkan1.0", "-S", (char *)stage, "-o", spv, src, NULL};
	int status = run(argv, &output, err);
	if (status == -1)
		goto out;
	if (status == -2) {
		aa_error_set(err, AA_ERR_INVALID, "", "%s: the compiler ran for over %d s and was stopped", shown_name,
			     COMPILE_SECONDS);
		goto out;
	}
	if (status != 0) {
		char msg[700];
		compile_message(output, src, shown_name, msg, sizeof msg);
		aa_error_set(err, AA_ERR_INVALID, "", "%s", msg);
		goto out;
	}
	if (read_file(spv, words, bytes) != 0) {
		aa_error_set(err, AA_ERR_INTERNAL, "", "%s compiled, but %s wrote no valid SPIR-V", shown_name, compiler());
		goto out;
	}
	if (dir[0])
		cache_store(dir, path, *words, *bytes);
	rc = 0;
out:
	free(output);
	unlink(src);
	unlink(spv);
	rmdir(work);
	return rc;
}
