#!/usr/bin/env bash
# Run every test binary given (or any program: make test adds the demo
# check), from the top of the tree, TEST_JOBS at a
# time (default 2, make test 3 on two cores: the binaries are
# independent, each works in its own mkdtemp folder; fewer jobs than that
# left a core idle through the tests that wait on INDI's simulators,
# daemons, sockets and mpirun), and close with one line that
# totals cmocka's counts: "total: N passed, M failed".  Each binary's
# output is printed whole when it ends.  The slowest binaries of the last
# run (BUILD_DIR/test-times.txt, seconds per binary) start first, so two
# long ones do not end the run alone.  Each line of test-times.txt is
# "BINARY WALL CPU": seconds of wall time, then CPU seconds (user+sys of
# the binary and every child it waited for), so a run can be modelled on
# free cores (CPU/jobs plus the waits on daemons, sockets and sleeps).
# A binary under OTHER_BUILD/tests/ runs with STRAY_BUILD=OTHER_BUILD.
# Usage: [TEST_JOBS=N] tests/run-tests.sh BUILD_DIR BINARY...
set -u
build=$1; shift
export STRAY_BUILD="$build"
export STRAY_BIN="$build/bin/stray"
# Third-party caches (PLplot's fonts) are not our leaks: tests/lsan.supp.
export LSAN_OPTIONS="suppressions=$(pwd)/tests/lsan.supp:print_suppressions=0"
jobs=${TEST_JOBS:-2}
times="$build/test-times.txt"

if [ "${1:-}" = --one ]; then	# internal: xargs calls back here
	dir=$2 t=$3
	# a binary of another tree (make test: build/asan/tests/...) runs
	# with that tree's stray
	case $t in
	*/tests/*) export STRAY_BUILD="${t%%/tests/*}"
		   export STRAY_BIN="$STRAY_BUILD/bin/stray" ;;
	esac
	log="$dir/$(echo "$t" | tr / _)"
	# bash's own timer: wall, user and sys seconds of the binary and
	# the children it reaped
	TIMEFORMAT='%R %U %S'
	{ time { "$t" >"$log.out" 2>&1; echo $? >"$log.rc"; } ; } 2>"$log.cpu"
	read -r wall user sys <"$log.cpu"
	printf '%s %s %s\n' "$t" "$wall" \
		"$(awk -v u="$user" -v s="$sys" 'BEGIN { printf "%.3f", u + s }')" \
		>"$log.time"
	# one binary's output at a time (flock: whole, not interleaved)
	flock "$dir" sh -c 'echo "== $1"; cat "$2"' sh "$t" "$log.out"
	exit 0
fi

dir=$(mktemp -d); trap 'rm -rf "$dir"' EXIT
# the last run's slowest first; one it has not timed (new, or every one
# on a fresh tree) before all, in the order given: it may be long
order=$(printf '%s\n' "$@" | awk -v f="$times" '
	BEGIN { while ((getline l < f) > 0) { split(l, a, " "); s[a[1]] = a[2] } }
	{ print (($0 in s) ? s[$0] : 1e9), NR, $0 }' |
	sort -k1,1gr -k2,2n | cut -d' ' -f3-)
[ $# -eq 0 ] || printf '%s\n' "$order" | xargs -d '\n' -P "$jobs" -n 1 "$0" "$build" --one "$dir"

passed=0; failed=0; broken=0
: >"$dir/times"
for t in "$@"; do
	log="$dir/$(echo "$t" | tr / _)"
	rc=$(cat "$log.rc" 2>/dev/null || echo 127)
	cat "$log.time" >>"$dir/times" 2>/dev/null
	p=$(sed -n 's/^\[  PASSED  \] \([0-9]*\) test.*/\1/p' "$log.out" 2>/dev/null | tail -n 1)
	f=$(sed -n 's/^\[  FAILED  \] \([0-9]*\) test.*/\1/p' "$log.out" 2>/dev/null | tail -n 1)
	passed=$((passed + ${p:-0})); failed=$((failed + ${f:-0}))
	if [ "$rc" -ne 0 ] && [ -z "$f" ]; then
		echo "!! $t exited $rc without a cmocka summary"
		broken=$((broken + 1))
	fi
done
# this run's times replace those it has; the others stay
[ -f "$times" ] && awk 'FILENAME == ARGV[1] { new[$1] = 1; next } !($1 in new)' \
	"$dir/times" "$times" >>"$dir/times"
cp "$dir/times" "$times" 2>/dev/null
echo "$build: $# test binaries, $jobs at a time, $broken broken;" \
	"$(awk 'NR == FNR { n[$1] = 1; next } ($1 in n) { w += $2; c += $3 }
	END { printf "%.0f s of wall time, %.0f CPU seconds summed over them", w, c }' \
	<(printf '%s\n' "$@") "$dir/times")"
echo "total: $passed passed, $((failed + broken)) failed"
[ "$failed" -eq 0 ] && [ "$broken" -eq 0 ]
