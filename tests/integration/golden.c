/* Golden values of the tests (see golden.h). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "golden.h"

#define KEY_MAX 160

struct entry {
	char key[KEY_MAX];
	double value;
	bool used;
};

static struct {
	char name[256];
	struct entry *file;  /* the values in the file */
	int file_count;
	struct entry *got;   /* the values computed, in order */
	int got_count, got_cap;
	int off, missing;
	bool loaded;
} g;

bool golden_updating(void)
{
	const char *out = getenv("AALAB_GOLDEN_OUT");
	return out && *out;
}

void golden_open(const char *name)
{
	free(g.file);
	free(g.got);
	memset(&g, 0, sizeof g);
	snprintf(g.name, sizeof g.name, "%s", name);
	if (golden_updating())
		return;
	const char *top = getenv("top_srcdir");
	char path[1024];
	snprintf(path, sizeof path, "%s/tests/golden/%s", top && *top ? top : ".", name);
	FILE *f = fopen(path, "r");
	if (!f)
		fail_msg("cannot read %s: run `make update-golden` to create it", path);
	char line[512];
	int cap = 0;
	while (fgets(line, sizeof line, f)) {
		line[strcspn(line, "\n")] = '\0';
		if (line[0] == '#' || line[0] == '\0')
			continue;
		char *tab = strrchr(line, '\t');
		if (!tab)
			fail_msg("%s: a line without a tab: %s", name, line);
		*tab = '\0';
		if (g.file_count == cap) {
			cap = cap ? cap * 2 : 256;
			g.file = realloc(g.file, (size_t)cap * sizeof *g.file);
			assert_non_null(g.file);
		}
		struct entry *e = &g.file[g.file_count++];
		snprintf(e->key, sizeof e->key, "%.*s", KEY_MAX - 1, line);
		e->value = strcmp(tab + 1, "nan") == 0 ? NAN : strtod(tab + 1, NULL);
		e->used = false;
	}
	fclose(f);
	g.loaded = true;
}

void golden_check(const char *key, double value, double tolerance)
{
	if (g.got_count == g.got_cap) {
		g.got_cap = g.got_cap ? g.got_cap * 2 : 256;
		g.got = realloc(g.got, (size_t)g.got_cap * sizeof *g.got);
		assert_non_null(g.got);
	}
	struct entry *got = &g.got[g.got_count++];
	snprintf(got->key, sizeof got->key, "%s", key);
	got->value = value;
	if (!g.loaded)
		return;
	for (int i = 0; i < g.file_count; i++) {
		struct entry *e = &g.file[i];
		if (strcmp(e->key, key) != 0)
			continue;
		e->used = true;
		bool ok = isnan(e->value) ? isnan(value) : fabs(value - e->value) <= tolerance;
		if (!ok) {
			printf("  GOLDEN %-44s %12.6f, pinned %12.6f (%+.6f, tolerance %g)\n", key, value, e->value,
			       value - e->value, tolerance);
			g.off++;
		}
		return;
	}
	printf("  GOLDEN %-44s %12.6f, not in %s\n", key, value, g.name);
	g.missing++;
}

void golden_finish(void)
{
	if (golden_updating()) {
		const char *out = getenv("AALAB_GOLDEN_OUT");
		FILE *f = fopen(out, "a");
		if (!f)
			fail_msg("cannot write %s", out);
		for (int i = 0; i < g.got_count; i++) {
			if (isnan(g.got[i].value))
				fprintf(f, "%s\tnan\n", g.got[i].key);
			else
				fprintf(f, "%s\t%.6f\n", g.got[i].key, g.got[i].value);
		}
		fclose(f);
		printf("  %d golden values of %s appended to %s\n", g.got_count, g.name, out);
		return;
	}
	int stale = 0;
	for (int i = 0; i < g.file_count; i++)
		if (!g.file[i].used) {
			printf("  GOLDEN %-44s pinned in %s but no longer computed\n", g.file[i].key, g.name);
			stale++;
		}
	printf("  %d golden values of %s: %d off, %d missing, %d stale\n", g.got_count, g.name, g.off, g.missing, stale);
	if (g.off || g.missing || stale)
		fail_msg("%s: %d values off, %d missing, %d stale. If the change is intended, run `make update-golden`, "
			 "review the diff and commit it", g.name, g.off, g.missing, stale);
}
