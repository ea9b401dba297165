# engine/scene: Makefile fragment, included from Makefile.am. aalab's own strict reading of OBJ (+ .mtl),
# OFF, PLY and STL files before assimp (mesh_text_check.c, one mesh_text_*.c per format) and its unit
# test; the materials of mesh files (mesh_file_materials.c, split from mesh_file.c); finding scenes by name
# (scene_files.c, split from scene_load.c); the files a load read, for the daemon's scene cache
# (scene_sources.c).
libaaengine_a_SOURCES += engine/scene/mesh_text_check.h engine/scene/mesh_text_check.c \
	engine/scene/mesh_text.h engine/scene/mesh_text_obj.c engine/scene/mesh_text_off.c \
	engine/scene/mesh_text_ply.c engine/scene/mesh_text_stl.c \
	engine/scene/mesh_file_loader.h engine/scene/mesh_file_materials.c engine/scene/scene_files.c \
	engine/scene/scene_sources.c

check_PROGRAMS += tests/unit/test_mesh_text_check
tests_unit_test_mesh_text_check_SOURCES = tests/unit/test_mesh_text_check.c
tests_unit_test_mesh_text_check_CFLAGS = $(TEST_CFLAGS)
tests_unit_test_mesh_text_check_LDADD = $(TEST_LIBS)
TESTS += tests/unit/test_mesh_text_check
