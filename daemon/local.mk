# daemon: aalabd, the long-running service: listeners, connections and the event loop (transport); the
# protocol, HTTP routes and streaming (handlers); the job queue and store; the GPU worker and its child
# process; the scene cache. Also the dashboard page it serves, systemd units and the man pages.
# In layers, lowest first (tests/layout/layers.py checks them): config; transport (knows nothing of jobs,
# calls up only through handlers.h); jobs (the store, scene cache, the worker thread and process);
# handlers (protocol ops, HTTP routes, streaming, farm routes); aalabd.c, which puts them together.
aalabd_SOURCES = \
	daemon/config.h daemon/config.c \
	daemon/loop.h daemon/loop.c daemon/transport.h daemon/handlers.h daemon/listen.c daemon/conn.c daemon/line_conn.c \
	daemon/protocol_parse.h daemon/protocol_parse.c daemon/http_parse.h daemon/http_parse.c \
	daemon/http_conn.h daemon/http_conn.c \
	daemon/jobs.h daemon/jobs.c daemon/scene_cache.c daemon/farm_jobs.c daemon/render_priority.h \
	daemon/render_priority.c daemon/worker_job.h daemon/worker_render.c daemon/worker_run.c \
	daemon/worker_process.h daemon/worker_process.c daemon/worker.c \
	daemon/daemon.h daemon/protocol.c daemon/stream.h daemon/stream.c daemon/http_routes.c \
	daemon/farm_routes.h daemon/farm_routes.c \
	daemon/aalabd.c
aalabd_CPPFLAGS = $(AM_CPPFLAGS) \
	-DAA_SOURCE_WEB_DIR='"$(abs_top_srcdir)/web"' -DAA_INSTALLED_WEB_DIR='"$(pkgdatadir)/web"'
aalabd_LDADD = $(ENGINE_LIBS)

# the dashboard page aalabd serves at /
webdir = $(pkgdatadir)/web
dist_web_DATA = web/index.html web/dashboard.css web/charts.js web/suite.js web/trends.js web/dashboard.js

# systemd units (the service names the installed aalabd and configuration file) and the configuration
systemdunitdir = $(prefix)/lib/systemd/system
dist_systemdunit_DATA = systemd/aalabd.socket
nodist_systemdunit_DATA = systemd/aalabd.service
dist_sysconf_DATA = systemd/aalabd.conf
EXTRA_DIST += systemd/aalabd.service.in
CLEANFILES += systemd/aalabd.service
systemd/aalabd.service: $(srcdir)/systemd/aalabd.service.in Makefile
	@$(MKDIR_P) systemd
	$(AM_V_GEN)sed -e 's|@bindir@|$(bindir)|g' -e 's|@sysconfdir@|$(sysconfdir)|g' \
		$(srcdir)/systemd/aalabd.service.in >$@

dist_man_MANS = docs/aalab.1 docs/aalabd.8
