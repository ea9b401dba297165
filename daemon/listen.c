/* Listening sockets: a Unix socket (mode 0660), TCP on HOST:PORT, sockets passed by systemd (LISTEN_FDS),
 * and the two tiny systemd protocols aalabd speaks itself: sd_notify datagrams and LISTEN_FDS. */
#include <arpa/inet.h>
#include <errno.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include "transport.h"

static int set_flags(int fd)
{
	int fl = fcntl(fd, F_GETFL);
	return fl < 0 || fcntl(fd, F_SETFL, fl | O_NONBLOCK) < 0 || fcntl(fd, F_SETFD, FD_CLOEXEC) < 0 ? -1 : 0;
}

int listen_unix(const char *path, char *err, size_t err_size)
{
	struct sockaddr_un sa = {.sun_family = AF_UNIX};
	if (strlen(path) >= sizeof sa.sun_path) {
		snprintf(err, err_size, "socket: path '%s' is longer than %zu bytes", path, sizeof sa.sun_path - 1);
		return -1;
	}
	memcpy(sa.sun_path, path, strlen(path) + 1);
	int fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
	if (fd < 0) {
		snprintf(err, err_size, "socket: %s", strerror(errno));
		return -1;
	}
	/* A socket file left by a daemon that died is removed; one a live daemon answers on is not. */
	int probe = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
	if (probe >= 0 && connect(probe, (struct sockaddr *)&sa, sizeof sa) == 0) {
		snprintf(err, err_size, "socket: another aalabd is listening on %s", path);
		close(probe);
		close(fd);
		return -1;
	}
	if (probe >= 0)
		close(probe);
	struct stat st;
	if (lstat(path, &st) == 0 && S_ISSOCK(st.st_mode))
		unlink(path);
	mode_t old = umask(0117); /* the socket is created 0660 */
	int rc = bind(fd, (struct sockaddr *)&sa, sizeof sa);
	umask(old);
	if (rc < 0 || chmod(path, 0660) < 0 || listen(fd, 64) < 0) {
		snprintf(err, err_size, "socket: cannot listen on %s: %s", path, strerror(errno));
		close(fd);
		return -1;
	}
	return fd;
}

static int split_host_port(const char *host_port, char *host, size_t hsize, char *port, size_t psize)
{
	const char *colon = strrchr(host_port, ':');
	if (!colon || colon == host_port || !colon[1])
		return -1;
	const char *h = host_port;
	size_t hlen = (size_t)(colon - host_port);
	if (h[0] == '[' && hlen >= 2 && h[hlen - 1] == ']') { /* [::1]:8080 */
		h++;
		hlen -= 2;
	}
	if (hlen >= hsize || strlen(colon + 1) >= psize)
		return -1;
	memcpy(host, h, hlen);
	host[hlen] = 0;
	snprintf(port, psize, "%s", colon + 1);
	return 0;
}

bool address_is_loopback(const char *host_port)
{
	char host[256], port[32];
	if (split_host_port(host_port, host, sizeof host, port, sizeof port))
		return false;
	return strcmp(host, "localhost") == 0 || strncmp(host, "127.", 4) == 0 || strcmp(host, "::1") == 0;
}

int check_tcp_address(const char *what, const char *host_port, char *err, size_t err_size)
{
	char host[256], port[32];
	if (split_host_port(host_port, host, sizeof host, port, sizeof port)) {
		snprintf(err, err_size, "%s: '%s' is not HOST:PORT", what, host_port);
		return -1;
	}
	struct addrinfo hints = {.ai_family = AF_UNSPEC, .ai_socktype = SOCK_STREAM, .ai_flags = AI_PASSIVE}, *ai;
	int gai = getaddrinfo(host, port, &hints, &ai);
	if (gai) {
		snprintf(err, err_size, "%s: %s: %s", what, host_port, gai_strerror(gai));
		return -1;
	}
	freeaddrinfo(ai);
	return 0;
}

int listen_tcp(const char *host_port, char *err, size_t err_size)
{
	char host[256], port[32];
	if (split_host_port(host_port, host, sizeof host, port, sizeof port)) {
		snprintf(err, err_size, "'%s' is not HOST:PORT", host_port);
		return -1;
	}
	struct addrinfo hints = {.ai_family = AF_UNSPEC, .ai_socktype = SOCK_STREAM, .ai_flags = AI_PASSIVE}, *ai;
	int gai = getaddrinfo(host, port, &hints, &ai);
	if (gai) {
		snprintf(err, err_size, "%s: %s", host_port, gai_strerror(gai));
		return -1;
	}
	int fd = socket(ai->ai_family, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0), one = 1;
	if (fd < 0 || setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one) < 0 ||
	    bind(fd, ai->ai_addr, ai->ai_addrlen) < 0 || listen(fd, 64) < 0) {
		snprintf(err, err_size, "cannot listen on %s: %s", host_port, strerror(errno));
		if (fd >= 0)
			close(fd);
		fd = -1;
	}
	freeaddrinfo(ai);
	return fd;
}

/* LISTEN_FDS: systemd passes sockets as descriptors 3, 4, ... when LISTEN_PID is this process.
 * LISTEN_FDNAMES (FileDescriptorName= in the .socket unit) says what each is: "http" serves HTTP, "tcp"
 * the protocol with a token; otherwise a Unix socket serves the protocol and an inet one needs the token. */
int listen_systemd(struct transport *t, char *err, size_t err_size)
{
	const char *pid = getenv("LISTEN_PID"), *fds = getenv("LISTEN_FDS"), *names = getenv("LISTEN_FDNAMES");
	if (!pid || !fds || strtol(pid, NULL, 10) != (long)getpid())
		return 0;
	int n = (int)strtol(fds, NULL, 10);
	char namebuf[1024] = "";
	snprintf(namebuf, sizeof namebuf, "%s", names ? names : "");
	char *save = NULL, *name = strtok_r(namebuf, ":", &save);
	for (int i = 0; i < n; i++, name = name ? strtok_r(NULL, ":", &save) : NULL) {
		int fd = 3 + i;
		if (t->listener_count == (int)(sizeof t->listeners / sizeof t->listeners[0]) || set_flags(fd)) {
			snprintf(err, err_size, "LISTEN_FDS: cannot use descriptor %d", fd);
			return -1;
		}
		struct sockaddr_storage ss;
		socklen_t len = sizeof ss;
		if (getsockname(fd, (struct sockaddr *)&ss, &len) < 0) {
			snprintf(err, err_size, "LISTEN_FDS: descriptor %d is not a socket", fd);
			return -1;
		}
		struct listener *l = &t->listeners[t->listener_count++];
		l->fd = fd;
		l->from_systemd = true;
		l->kind = name && strcmp(name, "http") == 0 ? CONN_HTTP : CONN_PROTOCOL;
		l->input = l->kind == CONN_HTTP ? http_input : line_input;
		l->tcp = ss.ss_family != AF_UNIX;
		snprintf(l->name, sizeof l->name, "systemd:%s", name ? name : "unnamed");
	}
	unsetenv("LISTEN_PID");
	unsetenv("LISTEN_FDS");
	unsetenv("LISTEN_FDNAMES");
	return n;
}

/* sd_notify: one datagram of "KEY=value" lines to the socket named by $NOTIFY_SOCKET ('@' = abstract). */
void sd_notifyf(const char *fmt, ...)
{
	const char *path = getenv("NOTIFY_SOCKET");
	if (!path || !*path)
		return;
	struct sockaddr_un sa = {.sun_family = AF_UNIX};
	size_t len = strlen(path);
	if (len >= sizeof sa.sun_path)
		return;
	memcpy(sa.sun_path, path, len);
	if (path[0] == '@')
		sa.sun_path[0] = 0;
	char msg[512];
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(msg, sizeof msg, fmt, ap);
	va_end(ap);
	int fd = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
	if (fd < 0)
		return;
	sendto(fd, msg, strlen(msg), MSG_NOSIGNAL, (struct sockaddr *)&sa,
	       (socklen_t)(offsetof(struct sockaddr_un, sun_path) + len));
	close(fd);
}

int sd_watchdog_interval_ms(void)
{
	const char *usec = getenv("WATCHDOG_USEC"), *pid = getenv("WATCHDOG_PID");
	if (!usec || (pid && strtol(pid, NULL, 10) != (long)getpid()))
		return 0;
	long long us = strtoll(usec, NULL, 10);
	return us > 0 ? (int)(us / 2000 > 0 ? us / 2000 : 1) : 0;
}
