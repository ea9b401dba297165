# Farm scale (issue 16): shards of a job, merging them, the Slurm scripts, and their tests. Makefile
# fragment, included from Makefile.am.
libaaengine_a_SOURCES += engine/shard.h engine/shard.c engine/metrics/flicker.c \
	engine/results/shard_results.h engine/results/shard_results.c engine/results/results_read.c
aalab_SOURCES += client/cmd_merge.c client/cmd_slurm.c

check_PROGRAMS += tests/unit/test_shard
tests_unit_test_shard_SOURCES = tests/unit/test_shard.c
tests_unit_test_shard_CFLAGS = $(TEST_CFLAGS)
tests_unit_test_shard_LDADD = $(TEST_LIBS)
TESTS += tests/unit/test_shard

SHARD_SCRIPT_TESTS = tests/shard_merge.sh
TESTS += $(SHARD_SCRIPT_TESTS)
EXTRA_DIST += $(SHARD_SCRIPT_TESTS) tests/integration/shard_check.py tests/integration/slurm_cluster.py

# a throwaway one-node Slurm cluster (root; skips where Slurm cannot run, fails under AALAB_REQUIRE_SLURM)
TESTS += tests/integration/slurm_farm.py
EXTRA_DIST += tests/integration/slurm_farm.py
