# bench: benchmarks that print ratios measured side by side (docs/benchmarks.md). bench/pass_cost times
# each pass on the GPU and each submission on the CPU, interleaved (bench/floor, bench/methods).
noinst_PROGRAMS += bench/pass_cost
bench_pass_cost_SOURCES = bench/pass_cost.c
bench_pass_cost_LDADD = $(ENGINE_LIBS)
EXTRA_DIST += bench/methods bench/metrics bench/floor bench/service bench/materials bench/hard-cases-long \
	bench/fuzz bench/fuzz-runs.tsv bench/reference-cache bench/stop-latency
