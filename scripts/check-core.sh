#!/usr/bin/env bash
# The libstray core must stay freestanding (architecture.md): no heap, no
# stdio, nothing but libm from outside (and the sanitizer runtime in the
# ASan build; the GOT the static linker itself makes, which the sanitizers'
# position-independent code names).  Fails listing any other symbol the core's objects need.  Usage: scripts/check-core.sh libstray_core.a
set -eu
allowed='^(erfc|exp|expm1|fabs|fmax|fmin|lgamma|log|log10|log1p|pow|sqrt|floor|ceil|__(asan|ubsan)_[a-z0-9_]*|_GLOBAL_OFFSET_TABLE_)$'
# Undefined symbols not defined elsewhere in the archive itself.
undef=$(nm -u "$1" | awk '/ U /{print $2}' | sort -u)
defined=$(nm --defined-only "$1" | awk 'NF==3{print $3}' | sort -u)
extern=$(comm -23 <(echo "$undef") <(echo "$defined"))
bad=$(echo "$extern" | grep -Ev "$allowed" || true)
if [ -n "$bad" ]; then
	echo "check-core: $1 uses symbols a freestanding core may not:" $bad
	exit 1
fi
echo "check-core: $1 is freestanding (needs only libm:" \
	$(echo "$extern" | grep -Ev '^(__(asan|ubsan)_|_GLOBAL_OFFSET_TABLE_)')")"
