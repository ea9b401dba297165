/* The default socket of aalabd and aalab (socket_path.h). */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "util/socket_path.h"

void aa_socket_fallback_dir(char *out, size_t size)
{
	snprintf(out, size, "/tmp/aalabd-%lu", (unsigned long)geteuid());
}

void aa_socket_default_path(char *out, size_t size)
{
	const char *xdg = getenv("XDG_RUNTIME_DIR"), *systemd = getenv("RUNTIME_DIRECTORY");
	if (xdg && *xdg)
		snprintf(out, size, "%.900s/aalabd.sock", xdg);
	else if (systemd && *systemd && !strchr(systemd, ':')) /* one folder, not a list */
		snprintf(out, size, "%.900s/aalabd.sock", systemd);
	else {
		char dir[64];
		aa_socket_fallback_dir(dir, sizeof dir);
		snprintf(out, size, "%s/aalabd.sock", dir);
	}
}

int aa_socket_dir_check(const char *socket_path, bool create, struct aa_error *err)
{
	char dir[64];
	aa_socket_fallback_dir(dir, sizeof dir);
	const size_t n = strlen(dir);
	if (strncmp(socket_path, dir, n) != 0 || socket_path[n] != '/' || strchr(socket_path + n + 1, '/'))
		return 0;
	if (create && mkdir(dir, 0700) != 0 && errno != EEXIST)
		return aa_error_set(err, AA_ERR_IO, "socket", "socket: cannot create %s: %s", dir, strerror(errno));
	struct stat st;
	if (lstat(dir, &st) != 0) {
		if (!create && errno == ENOENT)
			return 0; /* made at start */
		return aa_error_set(err, AA_ERR_IO, "socket", "socket: %s: %s", dir, strerror(errno));
	}
	if (!S_ISDIR(st.st_mode))
		return aa_error_set(err, AA_ERR_INVALID, "socket", "socket: %s is not a folder (a link or a file put "
				    "there?); remove it or give --socket", dir);
	if (st.st_uid != geteuid())
		return aa_error_set(err, AA_ERR_INVALID, "socket", "socket: %s belongs to uid %lu, not to this user "
				    "(uid %lu); remove it or give --socket", dir, (unsigned long)st.st_uid,
				    (unsigned long)geteuid());
	if (st.st_mode & 077)
		return aa_error_set(err, AA_ERR_INVALID, "socket", "socket: %s is open to others (mode %03o); it must "
				    "be 0700: chmod 700 %s", dir, (unsigned)(st.st_mode & 0777), dir);
	return 0;
}
