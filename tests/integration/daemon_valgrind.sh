#!/bin/sh
# Manual leak check of aalabd under valgrind (not part of `make check`: valgrind cannot run the
# AddressSanitizer build, and lavapipe under valgrind is slow). Run it from a build configured WITHOUT
# --enable-sanitizers:  top_builddir=$PWD top_srcdir=/path/to/aalab tests/integration/daemon_valgrind.sh
# (--keep-debuginfo keeps the names of libraries the Vulkan loader unloads, so suppressions match.)
# It runs one small job and a few requests, stops the daemon with SIGTERM and fails on any "definitely
# lost" or "indirectly lost" block in aalab's own code.
. "$(dirname "$0")/../lib.sh"
command -v valgrind >/dev/null 2>&1 || { echo "SKIP: valgrind not installed"; exit 77; }
sock="$TMP/aalabd.sock"
valgrind --leak-check=full --errors-for-leak-kinds=definite,indirect --error-exitcode=9 --keep-debuginfo=yes \
	--suppressions="$(dirname "$0")/valgrind.supp" --log-file="$TMP/valgrind.log" \
	"$top_builddir/aalabd" --socket "$sock" --state-dir "$TMP/state" --http 127.0.0.1:0 >"$TMP/daemon.log" 2>&1 &
daemon=$!
i=0
until grep -qs "aalabd: ready" "$TMP/daemon.log"; do
	i=$((i + 1)); [ $i -gt 3000 ] && { cat "$TMP/daemon.log"; fail "aalabd did not start"; finish; }
	sleep 0.1
done
expect_status 0 "a job runs under valgrind" -- "$AALAB" submit --watch --quiet --connect "unix:$sock" \
	--scene thin-wires --methods none --frames 1 --size 32x18 --reference-samples 2
expect_status 0 "list" -- "$AALAB" list --connect "unix:$sock"
expect_status 0 "get" -- "$AALAB" get 000001 --out "$TMP/got" --connect "unix:$sock"
kill -TERM $daemon
wait $daemon
status=$?
grep -E "definitely lost|indirectly lost|ERROR SUMMARY" "$TMP/valgrind.log"
[ $status -eq 0 ] && pass "no leaks or memory errors (valgrind exit $status)" || { fail "valgrind exit $status"; cat "$TMP/valgrind.log" | tail -80; }
finish
