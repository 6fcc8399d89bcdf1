#!/usr/bin/env bash
# test_testbed.sh - the real backends (libusb, hidapi on hidraw, libgpiod)
# run the demo's sweep, and a fault schedule, through the umockdev test
# bed (scripts/rig-testbed.sh), and their frames are compared byte for
# byte with the simulated backend's (tests/rig/testbed/compare_frames.py).
# Run from the top of the tree by tests/run-tests.sh; prints cmocka's
# summary lines so the totals count it.  Where umockdev cannot run, one
# "SKIP:" line says why and no test is counted as passed.
set -u
B=${STRAY_BUILD:-build}
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
# the emulated lab's device locks, not the machine's /run/lock (another
# worktree's test bed may run at the same time)
export STRAYRIGD_LOCK_DIR=$tmp
passed=0; failed=0

ok() { echo "[       OK ] $1"; passed=$((passed + 1)); }
bad() { echo "[  FAILED  ] $1: $2"; failed=$((failed + 1)); }

# A probe of the test bed itself: can umockdev run here at all?
B=$B scripts/rig-testbed.sh true >"$tmp/probe.log" 2>&1; rc=$?
if [ $rc -eq 77 ] || grep -q "libumockdev-preload" "$tmp/probe.log"; then
	echo "SKIP: umockdev test bed cannot run here: $(head -n 1 "$tmp/probe.log")"
	echo "[  PASSED  ] 0 test(s)."
	exit 0
fi

# sweep DIR CONFIG(real) -> runs the test bed; sim twin from the same file
sweep_pair() {
	local name=$1 cfg=$2
	sed 's/"backend": *"real"/"backend": "sim"/' "$cfg" >"$tmp/$name-sim.json"
	"$B/bin/strayrigd" --config "$tmp/$name-sim.json" --sweep "$tmp/$name-sim" \
		>"$tmp/$name-sim.log" 2>&1 ||
		{ bad "$name: simulated sweep" "$(tail -n 1 "$tmp/$name-sim.log")"; return 1; }
	B=$B scripts/rig-testbed.sh --config "$cfg" --log "$tmp/$name-tb.log" \
		"$B/bin/strayrigd" --config "$cfg" --sweep "$tmp/$name-real" \
		>"$tmp/$name-real.log" 2>&1; rc=$?
	if [ $rc -ne 0 ]; then
		bad "$name: real backends under the test bed" \
			"exit $rc: $(grep -v 'frames, theta' "$tmp/$name-real.log" | tail -n 3 | tr '\n' ' ')"
		return 1
	fi
	ok "$name: real backends under the test bed, no protocol violation"
	if python3 tests/rig/testbed/compare_frames.py "$tmp/$name-sim" \
		"$tmp/$name-real" >"$tmp/$name-cmp.log"; then
		ok "$name: $(cat "$tmp/$name-cmp.log")"
	else
		bad "$name: frames" "$(cat "$tmp/$name-cmp.log")"
	fi
}

echo "[ RUN      ] demo sweep (examples/rig-testbed.json)"
sweep_pair demo examples/rig-testbed.json
echo "[ RUN      ] fault schedule (tests/rig/testbed/faults.json)"
if sweep_pair faults tests/rig/testbed/faults.json; then
	# What the kernel would show for the schedule: three devices gone
	# and back with uevents, two URBs that never completed (the camera's
	# timeout and stall).
	line=$(grep "command exit" "$tmp/faults-tb.log")
	case "$line" in
	*"3 disconnects, 3 re-plugs, 2 URBs never completed, 6 faults fired"*)
		ok "faults: $line" ;;
	*) bad "faults: test bed summary" "$line" ;;
	esac
fi
echo "[ RUN      ] stray rig probe"
B=$B scripts/rig-testbed.sh "$B/bin/stray" rig probe \
	--config examples/rig-testbed.json >"$tmp/probe.out" 2>"$tmp/probe.err"
rc=$?
n_ok=$(grep -c '^[a-z]* *ok: ' "$tmp/probe.out")
if [ $rc -eq 0 ] && [ "$n_ok" -eq 5 ] &&
	grep -q '^probe: every device answered' "$tmp/probe.out"; then
	ok "probe: 5 devices found and answered once"
else
	bad "probe" "exit $rc, $n_ok devices ok: $(tail -n 2 "$tmp/probe.out" "$tmp/probe.err" | tr '\n' ' ')"
fi
echo "[ RUN      ] the test bed flags a host that breaks a protocol"
# A host writing an 8-byte report with id 0x09 to the wheel, whose
# descriptor has output report 0x01: one line naming it, exit 3.
B=$B scripts/rig-testbed.sh python3 -c \
	"import os; f = os.open('/dev/hidraw0', os.O_RDWR); os.write(f, bytes([9] * 8))" \
	>"$tmp/neg.out" 2>&1
rc=$?
if [ $rc -eq 3 ] && grep -q "wheel: output report of 8 bytes with id 0x09" "$tmp/neg.out"; then
	ok "negative control: wrong HID report id flagged, exit 3"
else
	bad "negative control" "exit $rc: $(head -n 2 "$tmp/neg.out" | tr '\n' ' ')"
fi
echo "[ RUN      ] rig/udev/99-straylight.rules names the default devices"
missing=""
for id in 0403:faf0 04b4:00f1 16c0:05df 16c0:05e0; do
	grep -q "idVendor}==\"${id%:*}\", ATTRS\{0,1\}{idProduct}==\"${id#*:}\"" \
		rig/udev/99-straylight.rules || missing="$missing $id"
done
# the same ids, as the probe found them under the test bed
for id in 0403:faf0 04b4:00f1 16c0:05df 16c0:05e0; do
	grep -q "found .* $id" "$tmp/probe.out" || missing="$missing probe:$id"
done
if [ -z "$missing" ]; then ok "udev rules: stage, camera, wheel, monitor"
else bad "udev rules" "no rule for$missing"; fi
total=$((passed + failed))
echo "[==========] $total test(s) run."
echo "[  PASSED  ] $passed test(s)."
[ $failed -eq 0 ] || { echo "[  FAILED  ] $failed test(s), listed above"; exit 1; }
