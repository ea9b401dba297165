# daemon: aalabd, the long-running service: listeners, connections and the event loop (transport); the
# protocol, HTTP routes and streaming (handlers); the job queue and store; the GPU worker and its child
# process; the scene cache. Also the dashboard page it serves, systemd units and the man pages.
aalabd_SOURCES = \
	daemon/aalabd.c daemon/daemon.h daemon/loop.h daemon/loop.c daemon/config.c daemon/listen.c \
	daemon/conn.c daemon/protocol.c daemon/stream.c daemon/http.c daemon/http_parse.h daemon/http_parse.c \
	daemon/protocol_parse.h daemon/protocol_parse.c \
	daemon/jobs.h daemon/jobs.c daemon/worker.h daemon/worker.c daemon/worker_process.c daemon/scene_cache.c \
	daemon/render_priority.c daemon/farm_routes.h daemon/farm_routes.c
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
