# engine/image: float RGBA images in memory and their files: PNG read and written directly, every other
# format through OpenImageIO in a module loaded on first use.
libaaengine_a_SOURCES += engine/image/image.h engine/image/image.c engine/image/image_files.c \
	engine/image/png_io.h engine/image/png_io.c engine/image/oiio_module.h

# OpenImageIO behind a C interface, as a module that image_files.c loads with dlopen on the first file
# that is not a PNG: OpenImageIO's ~260 libraries cost every process ~0.25 s to load and initialise.
pkglibexec_PROGRAMS += aalab-oiio.so
aalab_oiio_so_SOURCES = engine/image/image_io.cc engine/image/oiio_module.h engine/util/error.h
aalab_oiio_so_CXXFLAGS = $(AM_CXXFLAGS) -fPIC
aalab_oiio_so_LDFLAGS = $(AM_LDFLAGS) -shared
aalab_oiio_so_LDADD = $(OIIO_LIBS)
