#!/usr/bin/env bash
# The layout the architecture page promises (docs/architecture.md): no
# source file of the product over 600 lines (split by job), and no library
# reaching up into the `stray` command (tools/cli.h or another tools/
# header): a command's work is a library call, the same for `stray`,
# `stray-mpi` and Python.  Fails naming each file at fault.
# Usage: scripts/check-layout.sh
set -eu
cd "$(dirname "$0")/.."
libs=(libstray tracer diagnose frames mission review firmware_fdr rig)
bad=0
while read -r n f; do
	[ "$f" = total ] && continue
	if [ "$n" -gt 600 ]; then
		echo "check-layout: $f: $n lines (at most 600: split it by job)"
		bad=$((bad + 1))
	fi
done < <(find "${libs[@]}" tools mpi -name '*.c' -o -name '*.h' -o \
	-name '*.cpp' | sort | xargs wc -l)
while IFS=: read -r f line text; do
	echo "check-layout: $f:$line: a library includes a tools/ header: $text"
	bad=$((bad + 1))
done < <(grep -rnE --include='*.c' --include='*.h' --include='*.cpp' \
	'#include "(cli|commands|plot|fdr_options|trace_run|trace_focal)\.h"|#include "tools/' \
	"${libs[@]}" || true)
[ "$bad" -eq 0 ] || exit 1
echo "check-layout: no file over 600 lines, no library includes tools/"
