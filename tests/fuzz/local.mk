# libFuzzer targets (tests/fuzz/README.md): built by `make fuzz` after ./configure --enable-fuzzing
# CC=clang CXX=clang++; `make fuzz-smoke` runs each for FUZZ_SECONDS on its seed corpus (CI), bench/fuzz
# runs them long and keeps a log of executions.
FUZZ_TARGETS = tests/fuzz/fuzz_protocol tests/fuzz/fuzz_http tests/fuzz/fuzz_job_spec tests/fuzz/fuzz_scene \
	tests/fuzz/fuzz_mesh tests/fuzz/fuzz_image
EXTRA_DIST += tests/fuzz/README.md tests/fuzz/corpus tests/fuzz/replay.sh bench/fuzz bench/fuzz-runs.tsv \
	$(patsubst %,%.c,$(FUZZ_TARGETS))

# make check: each target replays its corpus (seeds and the inputs of fixed bugs) without libFuzzer
REPLAY_CPPFLAGS = $(AM_CPPFLAGS) -I$(srcdir)/daemon
check_PROGRAMS += tests/fuzz/replay_protocol tests/fuzz/replay_http tests/fuzz/replay_job_spec \
	tests/fuzz/replay_scene tests/fuzz/replay_mesh tests/fuzz/replay_image
tests_fuzz_replay_protocol_SOURCES = tests/fuzz/replay.c tests/fuzz/fuzz_protocol.c daemon/protocol_parse.c
tests_fuzz_replay_protocol_CPPFLAGS = $(REPLAY_CPPFLAGS)
tests_fuzz_replay_protocol_LDADD = $(JANSSON_LIBS)
tests_fuzz_replay_http_SOURCES = tests/fuzz/replay.c tests/fuzz/fuzz_http.c daemon/http_parse.c
tests_fuzz_replay_http_LDADD =
tests_fuzz_replay_http_CPPFLAGS = $(REPLAY_CPPFLAGS)
tests_fuzz_replay_job_spec_SOURCES = tests/fuzz/replay.c tests/fuzz/fuzz_job_spec.c
tests_fuzz_replay_job_spec_LDADD = $(ENGINE_LIBS)
tests_fuzz_replay_scene_SOURCES = tests/fuzz/replay.c tests/fuzz/fuzz_scene.c
tests_fuzz_replay_scene_LDADD = $(ENGINE_LIBS)
tests_fuzz_replay_mesh_SOURCES = tests/fuzz/replay.c tests/fuzz/fuzz_mesh.c
tests_fuzz_replay_mesh_LDADD = $(ENGINE_LIBS)
tests_fuzz_replay_image_SOURCES = tests/fuzz/replay.c tests/fuzz/fuzz_image.c
tests_fuzz_replay_image_LDADD = $(ENGINE_LIBS)
TESTS += tests/fuzz/replay.sh

if FUZZING
EXTRA_PROGRAMS = $(FUZZ_TARGETS)
CLEANFILES += $(FUZZ_TARGETS) fuzz-smoke.log
FUZZ_LINK = -fsanitize=fuzzer
FUZZ_CPPFLAGS = $(AM_CPPFLAGS) -I$(srcdir)/daemon
tests_fuzz_fuzz_protocol_SOURCES = tests/fuzz/fuzz_protocol.c daemon/protocol_parse.c
tests_fuzz_fuzz_protocol_CPPFLAGS = $(FUZZ_CPPFLAGS)
tests_fuzz_fuzz_protocol_LDFLAGS = $(AM_LDFLAGS) $(FUZZ_LINK)
tests_fuzz_fuzz_protocol_LDADD = $(JANSSON_LIBS)
tests_fuzz_fuzz_http_SOURCES = tests/fuzz/fuzz_http.c daemon/http_parse.c
tests_fuzz_fuzz_http_LDADD =
tests_fuzz_fuzz_http_CPPFLAGS = $(FUZZ_CPPFLAGS)
tests_fuzz_fuzz_http_LDFLAGS = $(AM_LDFLAGS) $(FUZZ_LINK)
tests_fuzz_fuzz_job_spec_SOURCES = tests/fuzz/fuzz_job_spec.c
tests_fuzz_fuzz_job_spec_LDFLAGS = $(AM_LDFLAGS) $(FUZZ_LINK)
tests_fuzz_fuzz_job_spec_LDADD = $(ENGINE_LIBS)
tests_fuzz_fuzz_scene_SOURCES = tests/fuzz/fuzz_scene.c
tests_fuzz_fuzz_scene_LDFLAGS = $(AM_LDFLAGS) $(FUZZ_LINK)
tests_fuzz_fuzz_scene_LDADD = $(ENGINE_LIBS)
tests_fuzz_fuzz_mesh_SOURCES = tests/fuzz/fuzz_mesh.c
tests_fuzz_fuzz_mesh_LDFLAGS = $(AM_LDFLAGS) $(FUZZ_LINK)
tests_fuzz_fuzz_mesh_LDADD = $(ENGINE_LIBS)
tests_fuzz_fuzz_image_SOURCES = tests/fuzz/fuzz_image.c
tests_fuzz_fuzz_image_LDFLAGS = $(AM_LDFLAGS) $(FUZZ_LINK)
tests_fuzz_fuzz_image_LDADD = $(ENGINE_LIBS)

# the generated shader headers first, as `make all` does (the engine library includes them)
# (and the OpenImageIO module fuzz_image reads non-PNG files through)
fuzz: $(BUILT_SOURCES)
	$(MAKE) $(AM_MAKEFLAGS) $(FUZZ_TARGETS) aalab-oiio.so
# CI: each target for FUZZ_SECONDS on a copy of its seed corpus; any crash or sanitizer report fails
FUZZ_SECONDS = 20
# mesh included: OBJ, OFF, PLY and STL files are read strictly by aalab before assimp 5.2 sees them
# (engine/scene/mesh_text_check.c), since its readers crashed or looped on inputs fuzz_mesh found within
# seconds; those inputs are replayed by make check.
FUZZ_SMOKE_TARGETS = protocol http job_spec scene mesh image
fuzz-smoke: fuzz
	$(srcdir)/bench/fuzz --seconds $(FUZZ_SECONDS) --build $(abs_top_builddir) --log fuzz-smoke.log $(FUZZ_SMOKE_TARGETS)
else
fuzz fuzz-smoke:
	@echo "the fuzz targets need ./configure --enable-fuzzing CC=clang CXX=clang++" >&2; exit 1
endif
.PHONY: fuzz fuzz-smoke
