#!/usr/bin/env bash
# Every equation of the method (the thesis's chapters 2 and 3, as listed in
# docs/architecture.md) is findable by its own number: `grep -rn "eq. 2.14"`
# must land on the line that implements it, not on a range such as
# "eq. 2.13-2.16".  Fails naming each equation no source line cites alone.
# Usage: scripts/check-equations.sh [DIR...]   (default: the code folders)
set -eu
cd "$(dirname "$0")/.."
dirs=("$@")
[ ${#dirs[@]} -gt 0 ] || dirs=(libstray tracer diagnose firmware_fdr rig mission frames tools mpi)
# The method's equations the code implements: eq. 2.1-2.18 (photometry and
# the false-detection model) and eq. 3.1-3.15 (the lab measurement and its
# reduction).  Chapter 3.4's trace and chapter 4's validation have none.
eqs=$(echo 2.{1..18} 3.{1..15})
missing=()
for e in $eqs; do
	re="eq\. ${e//./\\.}([^0-9-]|-[^0-9]|\$)"
	grep -rEq --include='*.c' --include='*.h' --include='*.cpp' "$re" \
		"${dirs[@]}" 2>/dev/null || missing+=("$e")
done
if [ ${#missing[@]} -gt 0 ]; then
	echo "check-equations: no line cites eq. ${missing[*]} by its own number"
	exit 1
fi
echo "check-equations: all $(echo $eqs | wc -w) equations cited by their own number"
