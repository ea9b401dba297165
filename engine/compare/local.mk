# engine/compare: two results folders side by side (`aalab compare`): pairing cases and methods, the
# load-corrected cost change, gates, text/JUnit/markdown output; and merging shards into one result.
libaaengine_a_SOURCES += engine/compare/compare.h engine/compare/compare.c engine/compare/compare_cost.h \
	engine/compare/compare_cost.c engine/compare/compare_output.c engine/compare/gate.c \
	engine/compare/shard_merge.h engine/compare/shard_merge.c
