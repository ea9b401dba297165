# tests: the tests of the command line (shell scripts that run aalab as a user would), golden values,
# durability under injected faults, and what every test program shares.

# A check program is built from its own .c with the engine library unless it says otherwise.
LDADD = $(TEST_LIBS)
AM_CFLAGS += $(CMOCKA_CFLAGS)

# the command line: refusals that name the field, --help against aalab(1), output folders, jobs end to
# end, `aalab diff`, mesh
# files and their warnings, user methods from the examples, suites, compare and JUnit, shards and merging,
# the bench scripts' smoke run, SSIM against scikit-image
SCRIPT_TESTS = tests/ssim_oracle.sh tests/cli_errors.sh tests/cli_help.sh tests/cli_outdir.sh tests/run_job.sh \
	tests/bench_smoke.sh tests/diff_cli.sh tests/cli_assets.sh tests/user_methods.sh \
	tests/farm_cli.sh tests/farm_cost.sh tests/shard_merge.sh
# hard cases: the self-measuring reference, the hard-case suite and its verdicts (tests/hardcases/), a
# scene far from the origin against its control (tests/camrel/), GBAA's edges (tests/gbaa/)
SCRIPT_TESTS += tests/reference_auto.sh tests/hard_cases.sh tests/hard_cases_long.sh \
	tests/far_from_origin.sh tests/gbaa_edges.sh
# what users read: no development history in help, man pages, README and docs; the job keys documented
SCRIPT_TESTS += tests/product_text.sh tests/docs_job_keys.sh
# the store of reference frames from the command line (tests/reference_cache.sh)
SCRIPT_TESTS += tests/reference_cache.sh
# method sweeps end to end: the configurations run, each family's front in results.json and the terminal
SCRIPT_TESTS += tests/sweep_run.sh
TESTS += $(SCRIPT_TESTS)
EXTRA_DIST += $(SCRIPT_TESTS) tests/lib.sh tests/lsan.supp tests/oracle/ssim_oracle.py tests/junit.xsd \
	tests/assets tests/hardcases/small-suite.json tests/hardcases/long-static.json \
	tests/hardcases/long_run_check.py tests/camrel/shift_scene.py tests/camrel/compare_frames.py \
	tests/gbaa/eye-plane.json tests/tools/daemon-tests-busy

# golden values (tests/golden/): `make update-golden` computes every golden file anew, shows the diff
# against the committed one and asks before replacing it (ACCEPT=yes replaces without asking; ACCEPT=no
# only shows). tests/golden/README.md.
EXTRA_DIST += tests/golden/quality.tsv tests/golden/temporal.tsv tests/golden/update.sh tests/golden/README.md
GOLDEN_TEST_BINARIES = tests/integration/test_golden tests/integration/test_temporal_long
update-golden: $(GOLDEN_TEST_BINARIES)
	@$(AM_TESTS_ENVIRONMENT) ACCEPT='$(ACCEPT)'; export ACCEPT; \
	$(SHELL) $(srcdir)/tests/golden/update.sh $(GOLDEN_TEST_BINARIES)
.PHONY: update-golden

# durability: aalabd and aalab, unchanged, under an LD_PRELOAD shim that records the order of their file
# calls and fails one on demand (tests/durability/fault_shim.c). Built without sanitizers; in sanitizer
# builds the tests preload the ASan runtime ahead of it.
check_PROGRAMS += tests/durability/fault_shim.so
tests_durability_fault_shim_so_SOURCES = tests/durability/fault_shim.c
tests_durability_fault_shim_so_CPPFLAGS =
tests_durability_fault_shim_so_CFLAGS = -std=c11 -Wall -Wextra -fPIC
tests_durability_fault_shim_so_LDFLAGS = -shared
tests_durability_fault_shim_so_LDADD = -ldl
DURABILITY_TESTS = tests/durability/results_atomic.py tests/durability/daemon_atomic.py
TESTS += $(DURABILITY_TESTS)
EXTRA_DIST += $(DURABILITY_TESTS) tests/durability/durability_lib.py

# the layout: no include goes up a layer of engine/ or a group of daemon/ (docs/architecture.md)
TESTS += tests/layout/layers.py
EXTRA_DIST += tests/layout/layers.py

# the store of reference frames the tests use (AM_TESTS_ENVIRONMENT's XDG_CACHE_HOME)
clean-local:
	rm -rf tests/xdg-cache

# What `make distcheck` runs in CI (.ci/run, `make distcheck TESTS='$(DISTCHECK_TESTS)'`): the tarball's
# tests that read what it ships (sources, docs, scenes, suites, web pages, golden values) and finish in
# minutes; the whole suite runs once, under the sanitizers, in the same CI run.
DISTCHECK_TESTS = $(UNIT_TESTS) tests/fuzz/replay.sh tests/layout/layers.py tests/product_text.sh \
	tests/docs_job_keys.sh tests/cli_help.sh tests/cli_errors.sh tests/run_job.sh \
	tests/integration/test_golden tests/integration/daemon_docs.py tests/integration/daemon_http.py
