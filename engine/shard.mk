# Farm scale (issue 16): shards of a job, merging them, the Slurm scripts, and their tests. Makefile
# fragment, included from Makefile.am.
libaaengine_a_SOURCES += engine/shard.h engine/shard.c engine/metrics/flicker.c \
	engine/results/shard_results.h engine/results/shard_results.c
aalab_SOURCES += client/cmd_merge.c client/cmd_slurm.c
