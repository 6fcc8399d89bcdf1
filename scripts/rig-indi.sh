#!/usr/bin/env bash
# rig-indi.sh [--log FILE] COMMAND [ARG...]
#
# Runs COMMAND with an INDI lab of INDI's own simulators (Debian
# indi-bin): indiserver on a free port with indi_simulator_ccd,
# indi_simulator_wheel, indi_simulator_rotator, indi_simulator_lightpanel
# as the lamp and a second light panel named "Beam Block".  COMMAND sees
#   STRAYRIGD_INDI_PORT  the port (strayrigd takes it over its config)
#   RIG_INDI_FIFO        indiserver's control FIFO ("stop DRIVER", ...)
#   RIG_INDI_PID         indiserver's pid (a fault test may kill it)
# The server and its drivers are stopped after.  Exit status: COMMAND's,
# or 77 when indiserver cannot run here (the reason on one line).
set -eu
log=/dev/null
if [ "${1:-}" = "--log" ]; then log=$2; shift 2; fi
[ $# -gt 0 ] || { sed -n '2,13p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
for b in indiserver indi_simulator_ccd indi_simulator_wheel \
	indi_simulator_rotator indi_simulator_lightpanel indi_getprop \
	indi_setprop; do
	if ! command -v "$b" >/dev/null; then
		echo "rig-indi: SKIP: $b not installed (Debian: indi-bin)" >&2
		exit 77
	fi
done
tmp=$(mktemp -d)
pid=
cleanup() {
	# The server's process group: indiserver and its drivers.
	[ -n "$pid" ] && kill -TERM -- "-$pid" 2>/dev/null
	[ -n "$pid" ] && wait "$pid" 2>/dev/null
	rm -rf "$tmp"
}
trap cleanup EXIT
trap 'exit 130' INT TERM
port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
mkfifo "$tmp/fifo"
# A socket of its own (-u): indiserver's default /tmp/indiserver is
# one per machine, and a second server would refuse to start.
setsid indiserver ${RIG_INDI_VERBOSE:+-v} -p "$port" -u "$tmp/sock" -f "$tmp/fifo" -r 10 \
	indi_simulator_ccd indi_simulator_wheel indi_simulator_rotator \
	indi_simulator_lightpanel >"$log" 2>&1 &
pid=$!
up=0
for _ in $(seq 50); do
	if indi_getprop -p "$port" -t 1 "Rotator Simulator.CONNECTION.*" \
		>/dev/null 2>&1; then up=1; break; fi
	kill -0 "$pid" 2>/dev/null || break
	sleep 0.1
done
if [ "$up" -ne 1 ]; then
	echo "rig-indi: SKIP: indiserver did not come up on port $port" >&2
	exit 77
fi
echo 'start indi_simulator_lightpanel -n "Beam Block"' >"$tmp/fifo"
for _ in $(seq 50); do
	indi_getprop -p "$port" -t 1 "Beam Block.CONNECTION.*" >/dev/null \
		2>&1 && break
	sleep 0.1
done
# The CCD simulator checks its exposures once per polling period (1 s by
# default): at 50 ms a short exposure takes about its own length.
indi_setprop -p "$port" "CCD Simulator.POLLING_PERIOD.PERIOD_MS=50" \
	>/dev/null 2>&1 || true
export STRAYRIGD_INDI_PORT=$port RIG_INDI_FIFO=$tmp/fifo RIG_INDI_PID=$pid
set +e
"$@"
rc=$?
exit $rc
