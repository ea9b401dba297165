# tests/mutation: the mutation tool (run by hand, about an hour: tests/mutation/README.md) and the fast
# check that make check runs: every mutant of the catalogue still applies to the code exactly once.
MUTATION_CHECKS = tests/mutation/check_applies.sh
TESTS += $(MUTATION_CHECKS)
EXTRA_DIST += $(MUTATION_CHECKS) tests/mutation/mutate.py tests/mutation/catalogue.ini tests/mutation/README.md

# The campaign itself (see tests/mutation/README.md for the options): niced, on a copy under $(MUTATION_DIR).
MUTATION_DIR = $${TMPDIR:-/tmp}/aalab-mutation
mutation:
	nice -n 19 /usr/bin/python3 $(srcdir)/tests/mutation/mutate.py --srcdir $(srcdir) --workdir $(MUTATION_DIR) \
		$(MUTATION_FLAGS)
.PHONY: mutation
