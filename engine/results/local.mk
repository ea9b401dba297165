# engine/results: what a run leaves: results.json written and read back, per-method summaries, the
# cost-quality front and the warnings that qualify it, suites' results and their expected verdicts,
# output folders, EXR frames.
libaaengine_a_SOURCES += engine/results/results.h engine/results/results_json.c \
	engine/results/results_read.c engine/results/summary.c engine/results/output_dir.c \
	engine/results/suite_results.c engine/results/exr_frames.c \
	engine/results/verdicts.h engine/results/verdicts.c engine/results/verdicts_expected.h \
	engine/results/front.h engine/results/front.c engine/results/warnings.h engine/results/warnings.c
