# tests/integration: C tests on the GPU (each through the engine set-up of fixture.c), and the tests of
# aalabd on real sockets (each starts and stops its own aalabd under a temporary directory).
GPU_TESTS = \
	tests/integration/test_engine \
	tests/integration/test_analytic_edges \
	tests/integration/test_msaa \
	tests/integration/test_alpha_rule \
	tests/integration/test_fxaa \
	tests/integration/test_smaa \
	tests/integration/test_cmaa2 \
	tests/integration/test_rsaa \
	tests/integration/test_temporal \
	tests/integration/test_temporal_jitter \
	tests/integration/test_temporal_stability_asaa_t2msaa \
	tests/integration/test_user_methods \
	tests/integration/test_timing \
	tests/integration/test_debug_targets \
	tests/integration/test_assets \
	tests/integration/test_golden \
	tests/integration/test_temporal_long \
	tests/integration/test_reference_store
# what each pins:
#  engine, analytic_edges: jobs end to end; methods against exact coverage of analytic edges
#  msaa, alpha_rule: MSAA's shading point on hardware and virtual samples; every method family's alpha rule
#  fxaa: fxaa and fxaa-cs agree within 1/255, beat none, refuse bad parameters
#  cmaa2: its passes; slanted edges closer to exact coverage, aligned edges untouched
#  smaa, rsaa: SMAA's passes and modes (T2x, S2x, 4x against 1x and msaa:2); rsaa 8 beats 4 beats none, every parameter mix runs, dense detail stays finite
#  temporal, temporal_jitter: TAA's history; quads at two depths move by the same sub-pixel jitter
#  temporal_stability_asaa_t2msaa: no NaN/Inf in history, 2,000 still frames within 0.5 dB, cuts reset
#  user_methods: a pass-through user method measured as copy, the contract's values, compile errors
#  timing: rotating method order and timing.repeat
#  debug_targets: a NaN held in an intermediate is caught only with the option on
#  assets: each material feature against known values and a golden image (tests/assets/golden/,
#    rewritten with AALAB_UPDATE_GOLDEN=1), skinned velocity, every method on every feature
#  reference_store: a run from the store has the metrics of one without it, to the byte; one byte of a
#    texture, the size, N, the driver version or a shader's SPIR-V each make it miss; auto goes on
#  golden, temporal_long: every method on every scene pinned in tests/golden/quality.tsv; the temporal
#    methods over 128 still frames, a pan and a cut (tests/golden/temporal.tsv)
GOLDEN_FIXTURE = tests/integration/golden.h tests/integration/golden.c
check_PROGRAMS += $(GPU_TESTS)
TESTS += $(GPU_TESTS)
tests_integration_test_engine_SOURCES = tests/integration/test_engine.c $(GPU_TEST_FIXTURE)
tests_integration_test_analytic_edges_SOURCES = tests/integration/test_analytic_edges.c $(GPU_TEST_FIXTURE)
tests_integration_test_msaa_SOURCES = tests/integration/test_msaa.c $(GPU_TEST_FIXTURE)
tests_integration_test_alpha_rule_SOURCES = tests/integration/test_alpha_rule.c $(GPU_TEST_FIXTURE)
tests_integration_test_fxaa_SOURCES = tests/integration/test_fxaa.c $(GPU_TEST_FIXTURE)
tests_integration_test_smaa_SOURCES = tests/integration/test_smaa.c $(GPU_TEST_FIXTURE)
tests_integration_test_cmaa2_SOURCES = tests/integration/test_cmaa2.c $(GPU_TEST_FIXTURE)
tests_integration_test_rsaa_SOURCES = tests/integration/test_rsaa.c $(GPU_TEST_FIXTURE)
tests_integration_test_temporal_SOURCES = tests/integration/test_temporal.c $(GPU_TEST_FIXTURE)
tests_integration_test_temporal_jitter_SOURCES = tests/integration/test_temporal_jitter.c $(GPU_TEST_FIXTURE)
tests_integration_test_temporal_stability_asaa_t2msaa_SOURCES = \
	tests/integration/test_temporal_stability_asaa_t2msaa.c $(GPU_TEST_FIXTURE)
tests_integration_test_user_methods_SOURCES = tests/integration/test_user_methods.c $(GPU_TEST_FIXTURE)
tests_integration_test_timing_SOURCES = tests/integration/test_timing.c $(GPU_TEST_FIXTURE)
tests_integration_test_debug_targets_SOURCES = tests/integration/test_debug_targets.c $(GPU_TEST_FIXTURE)
tests_integration_test_assets_SOURCES = tests/integration/test_assets.c $(GPU_TEST_FIXTURE)
tests_integration_test_reference_store_SOURCES = tests/integration/test_reference_store.c $(GPU_TEST_FIXTURE)
tests_integration_test_golden_SOURCES = tests/integration/test_golden.c $(GPU_TEST_FIXTURE) $(GOLDEN_FIXTURE)
tests_integration_test_temporal_long_SOURCES = tests/integration/test_temporal_long.c $(GPU_TEST_FIXTURE) \
	$(GOLDEN_FIXTURE)

# aalabd: protocol, jobs, restarts, limits, disk, configuration, HTTP, docs' examples, user methods, the
# command line through it, systemd, the dashboard, farm routes, priorities
DAEMON_TESTS = tests/integration/daemon_protocol.py tests/integration/daemon_jobs.py \
	tests/integration/daemon_recovery.py tests/integration/daemon_limits.py tests/integration/daemon_lockout.py \
	tests/integration/daemon_disk.py tests/integration/daemon_config.py tests/integration/daemon_http.py \
	tests/integration/daemon_docs.py tests/integration/daemon_user_methods.py \
	tests/integration/daemon_cli.sh \
	tests/integration/daemon_systemd.py tests/integration/protocol_example.sh \
	tests/integration/systemd_units.sh tests/integration/dashboard.sh \
	tests/integration/exr_over_threshold.py tests/integration/daemon_bounds.py \
	tests/integration/daemon_priority.py tests/integration/daemon_farm.py tests/integration/dashboard_trends.sh \
	tests/integration/daemon_reference_cache.sh tests/integration/daemon_retention.py tests/integration/daemon_stop.py \
	tests/integration/daemon_files.py tests/integration/daemon_state_lock.py tests/integration/daemon_socket_default.py \
	tests/integration/daemon_token_rules.py tests/integration/daemon_scene_paths.py tests/integration/daemon_fair_output.py
TESTS += $(DAEMON_TESTS)
EXTRA_DIST += $(DAEMON_TESTS) tests/integration/daemon_lib.py tests/integration/daemon_valgrind.sh \
	tests/integration/valgrind.supp

# report.html's viewer in headless Chromium (skipped when chromium is not installed); cdp.py drives it
TESTS += tests/integration/viewer_browser.py tests/integration/dashboard_browser.py
EXTRA_DIST += tests/integration/viewer_browser.py tests/integration/dashboard_browser.py tests/integration/cdp.py

# a throwaway one-node Slurm cluster (root; skips where Slurm cannot run, fails under AALAB_REQUIRE_SLURM)
TESTS += tests/integration/slurm_farm.py
EXTRA_DIST += tests/integration/slurm_farm.py tests/integration/shard_check.py tests/integration/slurm_cluster.py
