/* Where aalabd listens and aalab connects when neither is told (--socket, --connect, AALAB_CONNECT): the
 * one rule both use, so that they find each other with or without XDG_RUNTIME_DIR (containers, CI, su). */
#ifndef AA_SOCKET_PATH_H
#define AA_SOCKET_PATH_H

#include <stdbool.h>
#include <stddef.h>

#include "util/error.h"

/* /tmp/aalabd-UID: the folder of the fallback socket, private to the user (created 0700). */
void aa_socket_fallback_dir(char *out, size_t size);
/* $XDG_RUNTIME_DIR/aalabd.sock, else $RUNTIME_DIRECTORY/aalabd.sock (systemd's RuntimeDirectory=), else
 * /tmp/aalabd-UID/aalabd.sock. */
void aa_socket_default_path(char *out, size_t size);
/* When socket_path is in the fallback folder: creates the folder 0700 (create) and checks that it is a
 * folder, not a link, owned by this user and closed to everyone else; "socket: ..." in err otherwise (a
 * folder another user made in /tmp could hand the socket to them). Any other path: 0. */
int aa_socket_dir_check(const char *socket_path, bool create, struct aa_error *err);

#endif
