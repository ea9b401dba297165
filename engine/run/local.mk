# engine/run: running jobs: the engine object (device, upload cache), the job spec and its JSON, one
# job's frames (reference, then each method, scored), suites of cases, shards, and finding suite files.
libaaengine_a_SOURCES += engine/run/engine.h engine/run/engine_internal.h engine/run/engine.c \
	engine/run/job_spec.h engine/run/job_parse.h engine/run/job_spec.c engine/run/job_suite.c \
	engine/run/job_run.c engine/run/frame_scoring.h engine/run/frame_scoring.c engine/run/farm.h engine/run/suite_run.c engine/run/suite_files.c \
	engine/run/shard.h engine/run/shard.c engine/run/method_sweep.h engine/run/method_sweep.c
AM_CPPFLAGS += -DAA_SOURCE_SUITE_DIR='"$(abs_top_srcdir)/suites"' -DAA_INSTALLED_SUITE_DIR='"$(pkgdatadir)/suites"'
# the suites `aalab run NAME` finds, installed beside the scenes
suitesdir = $(pkgdatadir)/suites
dist_suites_DATA = suites/smoke.json suites/full.json suites/hard.json suites/hard-cases.json
