#!/usr/bin/env bash
# rig-testbed.sh [--config RIG.json] [--log FILE] COMMAND [ARG...]
#
# Runs COMMAND with the lab's devices (APT stage behind its FTDI bridge,
# camera, ND wheel and lamp monitor on hidraw, the GPIO chip) emulated
# under umockdev, answered by the simulators' device side
# (rig/testbed/testbed.c).  The config names the devices; default
# examples/rig-testbed.json.  Exit status: COMMAND's, or 3 when the test
# bed saw the host break a device protocol, or 77 when umockdev cannot run
# here (the reason on one line).
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
B=${B:-$here/build}
config=$here/examples/rig-testbed.json
log=()
while [ $# -gt 0 ]; do
	case "$1" in
	--config) config=$2; shift 2 ;;
	--log) log=(--log "$2"); shift 2 ;;
	*) break ;;
	esac
done
[ $# -gt 0 ] || { sed -n '2,10p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
if ! command -v umockdev-wrapper >/dev/null; then
	echo "rig-testbed: SKIP: umockdev-wrapper not installed (Debian: umockdev)" >&2
	exit 77
fi
if [ ! -x "$B/bin/rig-testbed" ] || [ ! -f "$B/lib/rig-testbed-shim.so" ]; then
	echo "rig-testbed: SKIP: $B/bin/rig-testbed not built (needs libumockdev-dev)" >&2
	exit 77
fi
export RIG_TESTBED_SHIM=$B/lib/rig-testbed-shim.so
exec umockdev-wrapper "$B/bin/rig-testbed" --config "$config" "${log[@]}" -- "$@"
