#!/bin/sh
# Every mutant of tests/mutation/catalogue.ini applies to the code exactly once (the campaign itself is too
# long for make check; this keeps its catalogue in step with the code). A failure names the mutant: re-target
# its snippet to the new code or delete it (tests/mutation/README.md).
top_srcdir=${top_srcdir:-$(cd "$(dirname "$0")/../.." && pwd)}
exec /usr/bin/python3 "$top_srcdir/tests/mutation/mutate.py" --check-applies --srcdir "$top_srcdir"
