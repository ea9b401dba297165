# engine/scene: scenes on the CPU: scene files, procedural and file meshes (aalab's own strict reading of
# OBJ, OFF, PLY and STL before assimp; glTF through assimp with its materials), textures, rigs, camera
# paths, and the files a load read (for aalabd's scene cache).
libaaengine_a_SOURCES += \
	engine/scene/scene.h engine/scene/scene_load.c engine/scene/scene_summary.c engine/scene/scene_json.h engine/scene/scene_json.c \
	engine/scene/mesh_procedural.h engine/scene/mesh_procedural.c engine/scene/mesh_file.h \
	engine/scene/mesh_file.c engine/scene/gltf_check.c engine/scene/scene_rig.c \
	engine/scene/camera_path.c engine/scene/texture.h engine/scene/texture.c engine/scene/font5x7.c \
	engine/scene/scene_polygons.c engine/scene/scene_query.c \
	engine/scene/mesh_text_check.h engine/scene/mesh_text_check.c \
	engine/scene/mesh_text.h engine/scene/mesh_text_obj.c engine/scene/mesh_text_off.c \
	engine/scene/mesh_text_ply.c engine/scene/mesh_text_stl.c \
	engine/scene/mesh_file_loader.h engine/scene/mesh_file_materials.c engine/scene/scene_files.c \
	engine/scene/scene_sources.c
