# tests/unit: C tests (cmocka) without a GPU, one file each. A program here is built from its own .c
# with the engine library (the default sources and LDADD of check programs, set in tests/local.mk).
UNIT_TESTS = \
	tests/unit/test_math \
	tests/unit/test_draw_order \
	tests/unit/test_metrics \
	tests/unit/test_flip \
	tests/unit/test_flip_shared \
	tests/unit/test_fourier \
	tests/unit/test_exact_coverage \
	tests/unit/test_scene \
	tests/unit/test_scene_known \
	tests/unit/test_mesh_text_check \
	tests/unit/test_mesh_files \
	tests/unit/test_shadow_plan \
	tests/unit/test_frame_plan \
	tests/unit/test_job_spec \
	tests/unit/test_sweep \
	tests/unit/test_param_ranges \
	tests/unit/test_known_values \
	tests/unit/test_sample_independence \
	tests/unit/test_smaa_textures \
	tests/unit/test_rsaa_table \
	tests/unit/test_user_method \
	tests/unit/test_debug_targets_count \
	tests/unit/test_results \
	tests/unit/test_report_viewer \
	tests/unit/test_verdicts \
	tests/unit/test_front \
	tests/unit/test_warnings \
	tests/unit/test_farm \
	tests/unit/test_shard \
	tests/unit/test_reference_key \
	tests/unit/test_reference_cache \
	tests/unit/test_compare_arithmetic
# what each pins:
#  math, draw_order: matrices and the order transparent draws sort in
#  metrics, flip, fourier: PSNR/SSIM on images with known answers, FLIP and the Fourier bands
#  flip_shared: FLIP's reference side made once per frame gives the one-shot map; the scorer's metrics equal each method's alone
#  exact_coverage: the analytic coverage of 2D test patterns
#  scene, scene_known: scene files, and a mesh file's node transform, uvs and material defaults
#  mesh_text_check, mesh_files: the strict OBJ/OFF/PLY/STL readers; every test asset, every broken file
#  shadow_plan, frame_plan: cascade fit to the view, and every shipped scene's and method's frame plan
#  job_spec, param_ranges: job files; every parameter of every method at its bounds and one past
#  sweep: method sweeps (fxaa:preset=10|20|39) expanded, their limit and what they refuse
#  known_values: Halton and Sobol' points, the reference's scrambled nets, jitter sequences, standard sample
#    positions, FXAA/SMAA presets
#  sample_independence: no method's sample positions coincide with the reference's
#  smaa_textures, rsaa_table: SMAA's generated look-up textures; RSAA's offset table and SADP
#  user_method: method files, parameters, the GLSL of a pass, SHA-256, compiling and the SPIR-V cache
#  debug_targets_count: the non-finite count on hand-made half, float and depth texels
#  results, report_viewer: results.json, the verdict and warnings panel, the viewer's data, worst regions,
#  EXR frames
#  front, warnings: the cost-quality front and its text; results.json's warnings[], each and its absence
#  verdicts, farm, shard: hard cases' verdicts, suites/labels/baselines/compare, shards and merging
#  reference_key, reference_cache: each part of a reference's key changes it; the store's entries (damaged
#    ones found and removed, writers of one key at once, least recently used out past the size)
#  compare_arithmetic: every number aalab compare prints, worked out by hand; what it refuses
check_PROGRAMS += $(UNIT_TESTS) tests/tools/metrics_tool
TESTS += $(UNIT_TESTS)
EXTRA_DIST += tests/unit/flip_images.h
