/* Finding suite files by name, as scenes are found (docs/job-format.md, "Suites"): $AALAB_SUITE_DIR,
 * then the source tree's suites/ (running from a build), then the installed ones under pkgdatadir. */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "run/farm.h"

static int suite_dirs(const char *dirs[3])
{
	int n = 0;
	const char *env = getenv("AALAB_SUITE_DIR");
	if (env && env[0])
		dirs[n++] = env;
#ifdef AA_SOURCE_SUITE_DIR
	dirs[n++] = AA_SOURCE_SUITE_DIR;
#endif
#ifdef AA_INSTALLED_SUITE_DIR
	dirs[n++] = AA_INSTALLED_SUITE_DIR;
#endif
	return n;
}

static int compare_names(const void *a, const void *b)
{
	return strcmp(*(char *const *)a, *(char *const *)b);
}

int aa_suite_list(char ***names, int *count)
{
	const char *dirs[3];
	int nd = suite_dirs(dirs), n = 0;
	char **list = NULL;
	for (int d = 0; d < nd; d++) {
		DIR *dir = opendir(dirs[d]);
		struct dirent *e;
		while (dir && (e = readdir(dir))) {
			size_t len = strlen(e->d_name);
			if (e->d_name[0] == '.' || len < 6 || strcmp(e->d_name + len - 5, ".json") != 0)
				continue;
			bool seen = false;
			for (int i = 0; i < n && !seen; i++)
				seen = strlen(list[i]) == len - 5 && !strncmp(list[i], e->d_name, len - 5);
			char **grown = seen ? list : realloc(list, (size_t)(n + 1) * sizeof *list);
			if (!grown)
				break;
			list = grown;
			if (!seen && (list[n] = strndup(e->d_name, len - 5)))
				n++;
		}
		if (dir)
			closedir(dir);
	}
	if (n > 1)
		qsort(list, (size_t)n, sizeof *list, compare_names);
	*names = list;
	*count = n;
	return 0;
}

int aa_suite_resolve(const char *name, char *out, size_t size, struct aa_error *err)
{
	bool plain = name[0] && name[0] != '.' && strlen(name) < 64;
	for (const char *p = name; plain && *p; p++)
		plain = (*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z') || (*p >= '0' && *p <= '9') ||
			*p == '-' || *p == '_' || *p == '.';
	if (!plain)
		return aa_error_set(err, AA_ERR_NOT_FOUND, "", "no job file '%s'", name);
	const char *dirs[3];
	int nd = suite_dirs(dirs);
	for (int d = 0; d < nd; d++) {
		int n = snprintf(out, size, "%s/%s.json", dirs[d], name);
		if (n > 0 && (size_t)n < size && access(out, R_OK) == 0)
			return 0;
	}
	char **names = NULL, list[400] = "";
	int count = 0;
	size_t used = 0;
	aa_suite_list(&names, &count);
	for (int i = 0; i < count; i++) {
		if (used < sizeof list)
			used += (size_t)snprintf(list + used, sizeof list - used, "%s%s", i ? ", " : "", names[i]);
		free(names[i]);
	}
	free(names);
	return aa_error_set(err, AA_ERR_NOT_FOUND, "", "no job file '%s', and no suite of that name (suites: %s)",
			    name, count ? list : "none found; set AALAB_SUITE_DIR");
}
