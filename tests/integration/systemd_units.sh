#!/bin/sh
# systemd/aalabd.service and aalabd.socket pass `systemd-analyze verify` (skipped where it is missing).
. "$(dirname "$0")/../lib.sh"
command -v systemd-analyze >/dev/null 2>&1 || { echo "SKIP: systemd-analyze not installed"; exit 77; }
# the unit as installed, but starting this build's aalabd with the shipped configuration
sed -e "s|@bindir@|$top_builddir|g" -e "s|@sysconfdir@|$top_srcdir/systemd|g" \
	"$top_srcdir/systemd/aalabd.service.in" >"$TMP/aalabd.service"
cp "$top_srcdir/systemd/aalabd.socket" "$TMP/"
expect_status 0 "systemd-analyze verify" -- systemd-analyze verify --man=no "$TMP/aalabd.socket" "$TMP/aalabd.service"
# verify prints problems as warnings without failing on all of them
if grep -v "Failed to .*/proc/\|Cannot .* bus\|Transport endpoint\|Failed to connect" "$TMP/err" | grep -q .; then
	fail "systemd-analyze reported:"; cat "$TMP/err"
else
	pass "no warnings"
fi
grep -q "^Type=notify" "$TMP/aalabd.service" && pass "Type=notify" || fail "Type=notify"
for opt in DynamicUser=yes StateDirectory=aalabd RuntimeDirectory=aalabd ProtectSystem=strict NoNewPrivileges=yes \
	PrivateTmp=yes RestrictAddressFamilies= WatchdogSec=; do
	grep -q "^$opt" "$TMP/aalabd.service" && pass "$opt" || fail "missing $opt"
done
# the sandbox: a device ACL of DRM devices only, no group a host may lack, /proc limited to our own
# processes, IP only where the listeners are, no privileged or resource syscalls
for opt in "DeviceAllow=char-drm rw" "DevicePolicy=closed" "ProtectProc=invisible" "ProcSubset=pid" \
	"IPAddressDeny=any" "IPAddressAllow=localhost" "SystemCallFilter=~@privileged @resources"; do
	grep -qx "$opt" "$TMP/aalabd.service" && pass "$opt" || fail "missing $opt"
done
grep -q "^SupplementaryGroups=" "$TMP/aalabd.service" && fail "SupplementaryGroups= fails (216/GROUP) where the group is missing" \
	|| pass "no SupplementaryGroups= (a host without a render group still starts it)"
# systemd-analyze's exposure score, offline (systemd 252 and later): at most 1.5
if systemd-analyze security --help 2>/dev/null | grep -q -- "--offline"; then
	systemd-analyze security --offline=true "$TMP/aalabd.service" >"$TMP/security" 2>&1
	score=$(sed -n 's/.*Overall exposure level for aalabd.service: \([0-9.]*\).*/\1/p' "$TMP/security")
	if [ -n "$score" ] && awk "BEGIN { exit !($score <= 1.5) }"; then
		pass "systemd-analyze security exposure $score <= 1.5"
	else
		fail "systemd-analyze security exposure '${score:-?}' is over 1.5:"; grep "✗" "$TMP/security"
	fi
else
	echo "SKIP: systemd-analyze security --offline needs systemd 252"
fi
# the shipped configuration file parses
expect_status 0 "the shipped aalabd.conf parses" -- "$top_builddir/aalabd" --config "$top_srcdir/systemd/aalabd.conf" --check
echo "max-connections = lots" >"$TMP/bad.conf"
expect_status 2 "a bad configuration is refused" -- "$top_builddir/aalabd" --config "$TMP/bad.conf" --check
expect_stderr "bad.conf:1: max-connections: expected a whole number" "and the error names file, line and key"
finish
