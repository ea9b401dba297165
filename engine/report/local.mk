# engine/report: report.html, one self-contained page: the verdict and warnings, tables, charts and the
# image viewer.
# viewer.js and viewer.css are edited as themselves and embedded at build time as C byte arrays
# (viewer_assets.h).
libaaengine_a_SOURCES += engine/report/report_html.c engine/report/report_viewer.c engine/report/report_parts.h \
	engine/report/report_charts.c engine/report/report_tables.c engine/report/report_style.c \
	engine/report/report_verdict.c engine/report/report_regions.c engine/report/report.h engine/report/suite_report.c
VIEWER_ASSETS = engine/report/viewer.js engine/report/viewer.css
EXTRA_DIST += $(VIEWER_ASSETS)
BUILT_SOURCES += engine/report/viewer_assets.h
CLEANFILES += engine/report/viewer_assets.h
AM_CPPFLAGS += -I$(builddir)/engine/report

engine/report/viewer_assets.h: $(VIEWER_ASSETS:%=$(srcdir)/%)
	@$(MKDIR_P) engine/report
	$(AM_V_GEN)( for kind in js css; do echo "static const char aa_viewer_$$kind[] = {"; \
	  od -An -v -tx1 $(srcdir)/engine/report/viewer.$$kind | sed 's/ \([0-9a-f][0-9a-f]\)/0x\1,/g'; \
	  echo "0x00};"; done ) >$@.tmp && mv $@.tmp $@
engine/report/report_viewer.$(OBJEXT): engine/report/viewer_assets.h
