# engine/results: Makefile fragment for report.html's image viewer, included from Makefile.am.
# viewer.js and viewer.css are edited as themselves and embedded into the library at build time as
# C byte arrays (viewer_assets.h), so the report stays one self-contained page.

libaaengine_a_SOURCES += engine/results/report_viewer.c engine/results/report_warnings.c \
	engine/results/report_regions.c engine/results/exr_frames.c
VIEWER_ASSETS = engine/results/viewer.js engine/results/viewer.css
EXTRA_DIST += $(VIEWER_ASSETS)
BUILT_SOURCES += engine/results/viewer_assets.h
CLEANFILES += engine/results/viewer_assets.h
AM_CPPFLAGS += -I$(builddir)/engine/results

engine/results/viewer_assets.h: $(VIEWER_ASSETS:%=$(srcdir)/%)
	@$(MKDIR_P) engine/results
	$(AM_V_GEN)( for kind in js css; do echo "static const char aa_viewer_$$kind[] = {"; \
	  od -An -v -tx1 $(srcdir)/engine/results/viewer.$$kind | sed 's/ \([0-9a-f][0-9a-f]\)/0x\1,/g'; \
	  echo "0x00};"; done ) >$@.tmp && mv $@.tmp $@
engine/results/report_viewer.$(OBJEXT): engine/results/viewer_assets.h

# the viewer in headless Chromium (skipped when chromium is not installed); cdp.py drives it
TESTS += tests/integration/viewer_browser.py
EXTRA_DIST += tests/integration/viewer_browser.py tests/integration/cdp.py

# the warnings panel, the viewer's data and frame scripts, worst regions and EXR frames, on made-up results
check_PROGRAMS += tests/unit/test_report_viewer
tests_unit_test_report_viewer_SOURCES = tests/unit/test_report_viewer.c
tests_unit_test_report_viewer_CFLAGS = $(TEST_CFLAGS)
tests_unit_test_report_viewer_LDADD = $(TEST_LIBS)
TESTS += tests/unit/test_report_viewer
