# issue 17 (hard cases): the self-measuring reference, the hard-case scenes' suite and its verdicts.
TESTS += tests/reference_auto.sh
EXTRA_DIST += tests/reference_auto.sh tests/hardcases.mk
