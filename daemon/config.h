/* aalabd's configuration: every key of aalabd.conf (aalabd(8)), its defaults, the file's parser and what a
 * reload may change. The lowest daemon layer: it calls nothing of the daemon. */
#ifndef AALABD_CONFIG_H
#define AALABD_CONFIG_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

struct config {
	char socket_path[108];
	char state_dir[1024];
	char tcp[300];            /* HOST:PORT or "" */
	char token_file[1024];
	char http[300];
	char web_dir[1024];
	char config_file[1024];
	char device[128];
	size_t max_request_bytes;   /* one JSON line, and one announced payload */
	int max_connections;          /* per listener: HTTP cannot take the protocol socket's slots */
	int max_connections_per_peer; /* per listener and peer (uid on the Unix socket, address on TCP) */
	int hello_timeout_s;          /* a TCP client that has not shown its token by then is dropped */
	int max_jobs_per_client;    /* queued + running */
	int max_queued_jobs;
	double max_job_budget;      /* width x height x frames x (reference samples + methods) */
	int idle_timeout_s;         /* no request and no watch */
	int slow_client_timeout_s;  /* output pending and none of it written */
	int request_timeout_s;      /* a started line or payload not completed */
	size_t client_buffer_bytes; /* output kept per client; beyond it frames are dropped from the stream */
	int retention_jobs;         /* finished jobs kept */
	int max_job_interruptions;  /* crashes in a row during one job before it is failed (0: never) */
	int render_nice;            /* nice levels the rendering threads run below the protocol loop */
	uint64_t retention_bytes;   /* bytes of finished jobs kept */
	uint64_t scene_cache_bytes;
	char reference_cache[1024];  /* the store of references: a folder, "off", or "" for STATE_DIR/references */
	uint64_t reference_cache_bytes;
	int drain_timeout_s;        /* SIGTERM: how long the running job may take to finish */
	bool allow_user_methods;    /* jobs may bring their own shaders; GPU work runs in a worker process */
	int job_time_limit_s;       /* the worker process is killed when a job runs longer (0: no limit) */
	int verbose;
};

void config_defaults(struct config *c);
/* Reads "key = value" lines; errors name the file, the line and the key. */
int config_load(struct config *c, const char *path, char *err, size_t err_size);
/* Applies the reloadable settings (limits, timeouts, retention, cache budget) of `from` to `to`. */
/* The folder of the store of references the configuration names ("" when it is off). */
void config_reference_cache_dir(const struct config *c, char *out, size_t size);
void config_apply_reload(struct config *to, const struct config *from);
int config_set(struct config *c, const char *name, const char *value, char *err, size_t err_size);
bool config_has_key(const char *name); /* a key of the file, and so an option --KEY VALUE */

#endif
