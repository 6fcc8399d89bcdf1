#!/usr/bin/env bash
# Run every test binary given, from the top of the tree, and close with one
# line that totals cmocka's counts: "total: N passed, M failed".
# Usage: tests/run-tests.sh BUILD_DIR BINARY...
set -u
build=$1; shift
export STRAY_BUILD="$build"
export STRAY_BIN="$build/bin/stray"
# Third-party caches (PLplot's fonts) are not our leaks: tests/lsan.supp.
export LSAN_OPTIONS="suppressions=$(pwd)/tests/lsan.supp:print_suppressions=0"
passed=0; failed=0; broken=0
log=$(mktemp); trap 'rm -f "$log"' EXIT
for t in "$@"; do
	echo "== $t"
	"$t" >"$log" 2>&1; rc=$?
	cat "$log"
	p=$(sed -n 's/^\[  PASSED  \] \([0-9]*\) test.*/\1/p' "$log" | tail -n 1)
	f=$(sed -n 's/^\[  FAILED  \] \([0-9]*\) test.*/\1/p' "$log" | tail -n 1)
	passed=$((passed + ${p:-0})); failed=$((failed + ${f:-0}))
	if [ "$rc" -ne 0 ] && [ -z "$f" ]; then
		echo "!! $t exited $rc without a cmocka summary"
		broken=$((broken + 1))
	fi
done
echo "$build: $# test binaries, $broken broken"
echo "total: $passed passed, $((failed + broken)) failed"
[ "$failed" -eq 0 ] && [ "$broken" -eq 0 ]
