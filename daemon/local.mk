# daemon: Makefile fragment, included from Makefile.am (keeps parallel work in separate files).
# aalabd, the client's service commands, the dashboard page, systemd units, man pages and daemon tests.

bin_PROGRAMS += aalabd
aalabd_SOURCES = \
	daemon/aalabd.c daemon/daemon.h daemon/loop.h daemon/loop.c daemon/config.c daemon/listen.c \
	daemon/conn.c daemon/protocol.c daemon/stream.c daemon/http.c daemon/http_parse.h daemon/http_parse.c \
	daemon/protocol_parse.h daemon/protocol_parse.c \
	daemon/jobs.h daemon/jobs.c daemon/worker.h daemon/worker.c daemon/worker_process.c daemon/scene_cache.c \
	daemon/render_priority.c
aalabd_CPPFLAGS = $(AM_CPPFLAGS) \
	-DAA_SOURCE_WEB_DIR='"$(abs_top_srcdir)/web"' -DAA_INSTALLED_WEB_DIR='"$(pkgdatadir)/web"'
aalabd_LDADD = $(ENGINE_LIBS)

# the client's service commands and its protocol connection
aalab_SOURCES += client/out_dir.h client/out_dir.c \
	client/job_args.c client/remote.c client/cmd_submit.c client/cmd_watch.c \
	client/cmd_status.c client/cmd_jobs.c client/cmd_cancel.c client/cmd_get.c

# the dashboard page aalabd serves at /
webdir = $(pkgdatadir)/web
dist_web_DATA = web/index.html

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

# integration tests on real sockets (each starts and stops its own aalabd under a temporary directory)
DAEMON_TESTS = tests/integration/daemon_protocol.py tests/integration/daemon_jobs.py \
	tests/integration/daemon_recovery.py tests/integration/daemon_limits.py tests/integration/daemon_lockout.py \
	tests/integration/daemon_disk.py tests/integration/daemon_config.py tests/integration/daemon_http.py \
	tests/integration/daemon_docs.py tests/integration/daemon_user_methods.py \
	tests/integration/daemon_cli.sh \
	tests/integration/daemon_systemd.py tests/integration/protocol_example.sh \
	tests/integration/systemd_units.sh tests/integration/dashboard.sh tests/cli_outdir.sh \
	tests/integration/exr_over_threshold.py
TESTS += $(DAEMON_TESTS)
EXTRA_DIST += $(DAEMON_TESTS) tests/integration/daemon_lib.py tests/integration/daemon_valgrind.sh \
	tests/integration/valgrind.supp

# Tests that run `aalab run` must not hand their job to an aalabd someone runs on the default socket:
# an address nobody listens on keeps them in-process (daemon tests pass --connect or AALAB_CONNECT).
AM_TESTS_ENVIRONMENT += AALAB_CONNECT=unix:/nonexistent/aalabd.sock; export AALAB_CONNECT;
