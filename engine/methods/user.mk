# user methods (docs/user-methods.md): method files of the user's GLSL, compiled at run time with
# glslangValidator through a SPIR-V cache; the examples of examples/methods/ and their tests.
libaaengine_a_SOURCES += engine/methods/user_method.h engine/methods/user_method.c \
	engine/methods/user_method_file.c engine/methods/glsl_compile.h engine/methods/glsl_compile.c \
	engine/sha256.h engine/sha256.c
# the compiler configure found is the one user shaders are compiled with ($AALAB_GLSLANG overrides it)
AM_CPPFLAGS += -DAA_GLSLANG='"$(GLSLANG)"'
# the client reads a job's method files, and sends them to aalabd with the job
aalab_SOURCES += client/method_files.c
