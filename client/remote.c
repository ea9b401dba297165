/* The client side of the aalabd protocol (docs/protocol.md): connecting over a Unix socket or TCP,
 * hello (with the bearer token on TCP), requests and replies as JSON lines with optional payloads. */
#include <errno.h>
#include <netdb.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include "client.h"
#include "util/file_open.h"
#include "util/socket_path.h"

struct aa_conn {
	int fd;
	char *buf;
	size_t len, cap;
};

/* The default: $AALAB_CONNECT, else the socket aalabd listens on when not told (util/socket_path.h:
 * $XDG_RUNTIME_DIR/aalabd.sock, else /tmp/aalabd-UID/aalabd.sock in a folder that is this user's alone)
 * when it is there, else the system service's socket. */
static void default_address(char *out, size_t size)
{
	const char *env = getenv("AALAB_CONNECT");
	char path[1024];
	struct aa_error e = {0};
	aa_socket_default_path(path, sizeof path);
	if (env && *env)
		snprintf(out, size, "%s", env);
	else if (access(path, F_OK) == 0 && aa_socket_dir_check(path, false, &e) == 0)
		snprintf(out, size, "unix:%s", path);
	else
		snprintf(out, size, "unix:/run/aalabd/aalabd.sock");
}

static int connect_unix(const char *path, char *err, size_t err_size)
{
	struct sockaddr_un sa = {.sun_family = AF_UNIX};
	if (strlen(path) >= sizeof sa.sun_path) {
		snprintf(err, err_size, "socket path too long: %s", path);
		return -1;
	}
	memcpy(sa.sun_path, path, strlen(path) + 1);
	int fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
	if (fd < 0 || connect(fd, (struct sockaddr *)&sa, sizeof sa) < 0) {
		snprintf(err, err_size, "cannot connect to %s: %s (is aalabd running?)", path, strerror(errno));
		if (fd >= 0)
			close(fd);
		return -1;
	}
	return fd;
}

static int connect_tcp(const char *host_port, char *err, size_t err_size)
{
	char host[256];
	const char *colon = strrchr(host_port, ':');
	if (!colon || (size_t)(colon - host_port) >= sizeof host) {
		snprintf(err, err_size, "connect: '%s' is not HOST:PORT", host_port);
		return -1;
	}
	memcpy(host, host_port, (size_t)(colon - host_port));
	host[colon - host_port] = 0;
	struct addrinfo hints = {.ai_family = AF_UNSPEC, .ai_socktype = SOCK_STREAM}, *ai;
	int gai = getaddrinfo(host, colon + 1, &hints, &ai);
	if (gai) {
		snprintf(err, err_size, "connect: %s: %s", host_port, gai_strerror(gai));
		return -1;
	}
	int fd = socket(ai->ai_family, SOCK_STREAM | SOCK_CLOEXEC, 0);
	if (fd < 0 || connect(fd, ai->ai_addr, ai->ai_addrlen) < 0) {
		snprintf(err, err_size, "cannot connect to %s: %s", host_port, strerror(errno));
		if (fd >= 0)
			close(fd);
		fd = -1;
	}
	freeaddrinfo(ai);
	return fd;
}

static const char *token_file_option; /* --token-file, over the environment */

void aa_conn_set_token_file(const char *path)
{
	token_file_option = path;
}

/* The token for TCP: the first line of --token-file's file, else $AALAB_TOKEN, else the first line of
 * $AALAB_TOKEN_FILE; *source says which (for an error that tells where a refused token came from). */
static void read_token(char *out, size_t size, char *source, size_t source_size)
{
	const char *t = getenv("AALAB_TOKEN"), *file = token_file_option ? token_file_option : getenv("AALAB_TOKEN_FILE");
	out[0] = 0;
	source[0] = 0;
	if (t && !token_file_option) {
		snprintf(out, size, "%s", t);
		snprintf(source, source_size, "$AALAB_TOKEN");
	} else if (file) {
		struct aa_error fe = {0};
		FILE *f = aa_file_fopen_regular(file, "", &fe); /* never blocks on a FIFO */
		if (f && fgets(out, (int)size, f))
			out[strcspn(out, "\r\n")] = 0;
		if (f)
			fclose(f);
		/* spaces and tabs around the token do not count, as for aalabd's token-file */
		size_t start = strspn(out, " \t"), len = strlen(out + start);
		memmove(out, out + start, len + 1);
		while (len > 0 && (out[len - 1] == ' ' || out[len - 1] == '\t'))
			out[--len] = 0;
		snprintf(source, source_size, "%s%s%s", token_file_option ? "--token-file " : "$AALAB_TOKEN_FILE ", file,
			 fe.code == AA_ERR_INVALID ? ", which is not a regular file (a FIFO, socket or device) and was not "
			 "read" : "");
	}
}

/* What a refused hello means, and what to do: a TCP daemon wants its token, missing or wrong. */
static void hello_error(json_t *r, const char *token, const char *source, char *err, size_t err_size)
{
	json_t *e = r ? json_object_get(r, "error") : NULL;
	const char *code = json_string_value(json_object_get(e, "code"));
	if (code && !strcmp(code, "unauthorized") && !token[0])
		snprintf(err, err_size, "hello: this aalabd wants its bearer token on TCP and none was sent%s%s: set "
			 "AALAB_TOKEN, or AALAB_TOKEN_FILE or --token-file to a file holding it (the daemon's "
			 "token-file)", source[0] ? ": " : "", source[0] ? source : "");
	else if (code && !strcmp(code, "unauthorized"))
		snprintf(err, err_size, "hello: this aalabd refused the token from %s: it is not the one in the "
			 "daemon's token-file; set AALAB_TOKEN, or AALAB_TOKEN_FILE or --token-file to a file holding "
			 "that one", source);
	else
		snprintf(err, err_size, "hello: %s", e ? json_string_value(json_object_get(e, "message")) : "no reply");
}

int aa_conn_open(const char *address, struct aa_conn **out, char *err, size_t err_size)
{
	char where[1100];
	if (address)
		snprintf(where, sizeof where, "%s", address);
	else
		default_address(where, sizeof where);
	bool tcp = strncmp(where, "tcp:", 4) == 0;
	int fd = tcp ? connect_tcp(where + 4, err, err_size)
		     : connect_unix(strncmp(where, "unix:", 5) == 0 ? where + 5 : where, err, err_size);
	if (fd < 0)
		return -1;
	struct aa_conn *c = calloc(1, sizeof *c);
	if (!c) {
		close(fd);
		snprintf(err, err_size, "out of memory");
		return -1;
	}
	c->fd = fd;
	char token[256], source[1200];
	read_token(token, sizeof token, source, sizeof source);
	json_t *hello = json_pack("{ss si ss}", "op", "hello", "version", 1, "client", "aalab " PACKAGE_VERSION);
	if (tcp)
		json_object_set_new(hello, "token", json_string(token));
	json_t *r = aa_conn_request(c, hello, NULL, NULL);
	json_decref(hello);
	if (!r || !json_is_true(json_object_get(r, "ok"))) {
		hello_error(r, token, source, err, err_size);
		json_decref(r);
		aa_conn_close(c);
		return -1;
	}
	json_decref(r);
	*out = c;
	return 0;
}

void aa_conn_close(struct aa_conn *c)
{
	if (!c)
		return;
	close(c->fd);
	free(c->buf);
	free(c);
}

int aa_conn_send(struct aa_conn *c, json_t *msg, const void *payload, size_t size)
{
	if (payload)
		json_object_set_new(msg, "payload", json_integer((json_int_t)size));
	char *text = json_dumps(msg, JSON_COMPACT);
	if (!text)
		return -1;
	size_t n = strlen(text);
	text[n] = '\n';
	int rc = 0;
	for (size_t off = 0; off < n + 1 && rc == 0;) {
		ssize_t w = send(c->fd, text + off, n + 1 - off, MSG_NOSIGNAL);
		if (w <= 0 && errno != EINTR)
			rc = -1;
		else if (w > 0)
			off += (size_t)w;
	}
	free(text);
	for (size_t off = 0; payload && off < size && rc == 0;) {
		ssize_t w = send(c->fd, (const char *)payload + off, size - off, MSG_NOSIGNAL);
		if (w <= 0 && errno != EINTR)
			rc = -1;
		else if (w > 0)
			off += (size_t)w;
	}
	return rc;
}

static int fill(struct aa_conn *c, size_t want)
{
	while (c->len < want || want == 0) {
		if (c->cap - c->len < 65536) {
			size_t cap = c->cap ? c->cap * 2 : 131072;
			char *b = realloc(c->buf, cap);
			if (!b)
				return -1;
			c->buf = b;
			c->cap = cap;
		}
		ssize_t n = recv(c->fd, c->buf + c->len, c->cap - c->len, 0);
		if (n < 0 && errno == EINTR)
			continue;
		if (n <= 0)
			return -1;
		c->len += (size_t)n;
		if (want == 0)
			return 0;
	}
	return 0;
}

json_t *aa_conn_read(struct aa_conn *c, char **payload, size_t *size)
{
	char *nl;
	while (!(nl = c->len ? memchr(c->buf, '\n', c->len) : NULL))
		if (fill(c, 0))
			return NULL;
	size_t line = (size_t)(nl - c->buf) + 1;
	json_t *msg = json_loadb(c->buf, line - 1, 0, NULL);
	memmove(c->buf, c->buf + line, c->len - line);
	c->len -= line;
	if (!msg)
		return NULL;
	json_t *p = json_object_get(msg, "payload");
	if (payload)
		*payload = NULL;
	if (size)
		*size = 0;
	if (json_is_integer(p)) {
		size_t n = (size_t)json_integer_value(p);
		if (fill(c, n)) {
			json_decref(msg);
			return NULL;
		}
		if (payload) {
			*payload = malloc(n ? n : 1);
			if (*payload)
				memcpy(*payload, c->buf, n);
			*size = n;
		}
		memmove(c->buf, c->buf + n, c->len - n);
		c->len -= n;
	}
	return msg;
}

json_t *aa_conn_request(struct aa_conn *c, json_t *msg, char **payload, size_t *size)
{
	if (aa_conn_send(c, msg, NULL, 0))
		return NULL;
	return aa_conn_read(c, payload, size);
}

int aa_reply_status(const char *cmd, json_t *reply)
{
	if (!reply) {
		fprintf(stderr, "aalab %s: the daemon closed the connection\n", cmd);
		return AA_EXIT_FAILED;
	}
	if (json_is_true(json_object_get(reply, "ok")))
		return AA_EXIT_OK;
	json_t *e = json_object_get(reply, "error");
	const char *code = json_string_value(json_object_get(e, "code")), *path = json_string_value(json_object_get(e, "path"));
	char lead[64];
	snprintf(lead, sizeof lead, "aalab %s: ", cmd);
	aa_print_field_error(lead, path, json_string_value(json_object_get(e, "message")));
	/* the request was at fault: bad input, unknown job, over a limit */
	static const char *const usage_codes[] = {"invalid", "not_found", "limit", "bad_request", "too_large", NULL};
	for (int i = 0; code && usage_codes[i]; i++)
		if (!strcmp(code, usage_codes[i]))
			return AA_EXIT_USAGE;
	return AA_EXIT_FAILED;
}

int aa_service_args(const char *cmd, const char *help, int argc, char **argv, struct aa_service_args *a)
{
	enum { OPT_CONNECT = 256, OPT_JSON, OPT_STATE, OPT_OUT, OPT_FILE, OPT_NO_IMAGES, OPT_LABEL, OPT_SUITE, OPT_HELP,
	       OPT_TOKEN_FILE, OPT_NO_WAIT };
	static const struct option opts[] = {
		{"connect", required_argument, 0, OPT_CONNECT}, {"json", no_argument, 0, OPT_JSON},
		{"state", required_argument, 0, OPT_STATE}, {"out", required_argument, 0, OPT_OUT},
		{"file", required_argument, 0, OPT_FILE}, {"no-images", no_argument, 0, OPT_NO_IMAGES},
		{"label", required_argument, 0, OPT_LABEL}, {"suite", required_argument, 0, OPT_SUITE},
		{"token-file", required_argument, 0, OPT_TOKEN_FILE}, {"no-wait", no_argument, 0, OPT_NO_WAIT},
		{"help", no_argument, 0, OPT_HELP}, {0, 0, 0, 0},
	};
	memset(a, 0, sizeof *a);
	int c, idx;
	optind = 1;
	while ((c = getopt_long(argc, argv, "", opts, &idx)) != -1) {
		switch (c) {
		case OPT_CONNECT: a->connect = optarg; break;
		case OPT_JSON: a->json = true; break;
		case OPT_STATE: a->state = optarg; break;
		case OPT_OUT: a->out = optarg; break;
		case OPT_FILE: a->file = optarg; break;
		case OPT_NO_IMAGES: a->no_images = true; break;
		case OPT_LABEL:
			if (a->label_count >= 16) {
				fprintf(stderr, "aalab %s: more than 16 --label filters\n", cmd);
				return -1;
			}
			a->labels[a->label_count++] = optarg;
			break;
		case OPT_SUITE: a->suite = optarg; break;
		case OPT_TOKEN_FILE: aa_conn_set_token_file(optarg); break;
		case OPT_NO_WAIT: a->no_wait = true; break;
		case OPT_HELP: fputs(help, stdout); return 1;
		default: fputs(help, stderr); return -1;
		}
		/* each command's help lists the options it takes; the others are refused */
		char named[32];
		snprintf(named, sizeof named, "--%s ", opts[idx].name);
		if (c != OPT_CONNECT && c != OPT_JSON && c != OPT_TOKEN_FILE && !strstr(help, named)) {
			fprintf(stderr, "aalab %s: --%s does not apply here\n", cmd, opts[idx].name);
			return -1;
		}
	}
	a->job = optind < argc ? argv[optind] : NULL;
	if (argc - optind > 1) {
		fprintf(stderr, "aalab %s: unexpected argument '%s'\n", cmd, argv[optind + 1]);
		return -1;
	}
	return 0;
}
