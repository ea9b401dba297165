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
# a watch with rgba8 frames (the shared frame cache), a refused payload and HTTP requests that end the
# connection: the paths that keep or close memory and connections
port=$(sed -n 's/^aalabd: listening (http) on 127.0.0.1://p' "$TMP/daemon.log")
expect_status 0 "watch with frames, a bad payload, HTTP close and a bad HTTP request" -- python3 -c '
import socket, sys
s = socket.socket(socket.AF_UNIX); s.connect(sys.argv[1]); f = s.makefile("rb")
s.sendall(b"{\"op\":\"watch\",\"job\":\"000001\",\"frames\":\"rgba8\"}\n")
while True:
    line = f.readline()
    if b"payload" in line:
        import json; f.read(json.loads(line)["payload"])
    if b"watch_end" in line: break
s.sendall(b"{\"op\":\"submit\",\"job\":{},\"payload\":-1}\n"); f.readline()
for req in (b"GET /healthz HTTP/1.1\r\nHost: a\r\nConnection: close\r\n\r\n", b"GET / HTTP/1.1\r\n\r\n"):
    h = socket.create_connection(("127.0.0.1", int(sys.argv[2]))); h.sendall(req)
    while h.recv(4096): pass
' "$sock" "$port"
kill -TERM $daemon
wait $daemon
status=$?
grep -E "definitely lost|indirectly lost|ERROR SUMMARY" "$TMP/valgrind.log"
[ $status -eq 0 ] && pass "no leaks or memory errors (valgrind exit $status)" || { fail "valgrind exit $status"; cat "$TMP/valgrind.log" | tail -80; }
finish
