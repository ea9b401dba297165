# engine/util: what every layer may use and that knows nothing of rendering: errors that name the field
# at fault and suggest what was meant, vectors and matrices, SHA-256, Halton points, the checks of JSON
# fields, whole files read and written atomically.
libaaengine_a_SOURCES += engine/util/error.h engine/util/error.c engine/util/mat4.h engine/util/mat4.c \
	engine/util/sha256.h engine/util/sha256.c engine/util/halton.h engine/util/halton.c engine/util/env_flag.h engine/util/env_flag.c \
	engine/util/json_text.h engine/util/json_text.c engine/util/file_name.h engine/util/file_name.c \
	engine/util/file_io.h engine/util/file_io.c engine/util/file_open.h engine/util/file_open.c \
	engine/util/socket_path.h engine/util/socket_path.c \
	engine/util/suggest.h engine/util/suggest.c
