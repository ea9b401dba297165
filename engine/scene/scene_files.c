/* Finding scenes: the scene folders ($AALAB_SCENE_DIR, the source tree's, the installed one), the names
 * they hold (aalab scenes) and a name or path resolved to its file. Loading one is scene_load.c's. */
#include <dirent.h>
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "scene/scene_json.h"

static int scene_dirs(const char *dirs[3])
{
	int n = 0;
	const char *env = getenv("AALAB_SCENE_DIR");
	if (env && env[0])
		dirs[n++] = env;
#ifdef AA_SOURCE_SCENE_DIR
	dirs[n++] = AA_SOURCE_SCENE_DIR;
#endif
#ifdef AA_INSTALLED_SCENE_DIR
	dirs[n++] = AA_INSTALLED_SCENE_DIR;
#endif
	return n;
}

static int cmp_names(const void *a, const void *b)
{
	return strcmp(*(char *const *)a, *(char *const *)b);
}

int aa_scene_list(char ***names, int *count)
{
	const char *dirs[3];
	int nd = scene_dirs(dirs), n = 0, cap = 0;
	char **list = NULL;
	for (int d = 0; d < nd; d++) {
		DIR *dir = opendir(dirs[d]);
		if (!dir)
			continue;
		struct dirent *e;
		while ((e = readdir(dir))) {
			if (e->d_name[0] == '.' || !sj_ends_with(e->d_name, ".json"))
				continue;
			size_t len = strlen(e->d_name) - 5;
			bool dup = false;
			for (int i = 0; i < n && !dup; i++)
				dup = strlen(list[i]) == len && strncmp(list[i], e->d_name, len) == 0;
			if (dup)
				continue;
			if (n == cap) {
				cap = cap ? cap * 2 : 16;
				char **nl = realloc(list, (size_t)cap * sizeof *nl);
				if (!nl)
					break;
				list = nl;
			}
			if ((list[n] = strndup(e->d_name, len)))
				n++;
		}
		closedir(dir);
	}
	if (n > 1)
		qsort(list, (size_t)n, sizeof *list, cmp_names);
	*names = list;
	*count = n;
	return 0;
}

int aa_scene_resolve(const char *name_or_path, char *out_path, size_t out_size, struct aa_error *err)
{
	const char *name = name_or_path;
	if (!name || !name[0])
		return aa_error_set(err, AA_ERR_INVALID, "scene", "no scene given");
	if (sj_ends_with(name, ".json")) {
		if (access(name, R_OK) != 0)
			return aa_error_set(err, AA_ERR_NOT_FOUND, "scene", "scene file '%s' not found", name);
		if (strlen(name) >= out_size)
			return aa_error_set(err, AA_ERR_INVALID, "scene", "scene path too long");
		memcpy(out_path, name, strlen(name) + 1);
		return 0;
	}
	bool ok = name[0] != '.' && strlen(name) < AA_NAME_MAX;
	for (const char *p = name; *p && ok; p++)
		ok = (*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z') || (*p >= '0' && *p <= '9') || *p == '-' ||
		     *p == '_' || *p == '.';
	if (!ok)
		return aa_error_set(err, AA_ERR_INVALID, "scene",
				    "'%s' is not a scene name (letters, digits, '-', '_'); for a file give a path "
				    "ending in .json", name);
	const char *dirs[3];
	int nd = scene_dirs(dirs);
	for (int d = 0; d < nd; d++) {
		char joined[PATH_MAX], real_dir[PATH_MAX], real_file[PATH_MAX];
		int n = snprintf(joined, sizeof joined, "%s/%s.json", dirs[d], name);
		if (n <= 0 || (size_t)n >= sizeof joined || access(joined, R_OK) != 0)
			continue;
		/* A scene name stays inside its scene folder: a symlink out of it (passwd.json -> /etc/passwd)
		 * is refused without reading, or quoting, the file it points to. */
		size_t dl = realpath(dirs[d], real_dir) ? strlen(real_dir) : 0;
		if (!dl || !realpath(joined, real_file) || strncmp(real_file, real_dir, dl) != 0 ||
		    (real_file[dl] != '/' && strcmp(real_dir, "/") != 0))
			return aa_error_set(err, AA_ERR_INVALID, "scene", "scene '%s' leads out of its scene folder "
					    "(a symbolic link); refused", name);
		if (strlen(real_file) >= out_size)
			return aa_error_set(err, AA_ERR_INVALID, "scene", "scene path too long");
		memcpy(out_path, real_file, strlen(real_file) + 1);
		return 0;
	}
	char **names = NULL, list[400] = "";
	int count = 0;
	size_t used = 0;
	aa_scene_list(&names, &count);
	for (int i = 0; i < count; i++) {
		int n = snprintf(list + used, sizeof list - used, "%s%s", i ? ", " : "", names[i]);
		if (n > 0 && (size_t)n < sizeof list - used)
			used += (size_t)n;
		free(names[i]);
	}
	free(names);
	return aa_error_set(err, AA_ERR_NOT_FOUND, "scene", "unknown scene '%s' (scenes: %s)", name,
			    count ? list : "none found; set AALAB_SCENE_DIR");
}
