#!/usr/bin/env bash
# `make install` works and the installed library is usable through
# pkg-config: install into a scratch prefix, build a small program against
# `pkg-config stray`, run it.  Usage: scripts/check-install.sh BUILD_DIR
set -eu
build=$1
prefix=$(mktemp -d)
trap 'rm -rf "$prefix"' EXIT
env -u MAKEFLAGS -u MFLAGS make --no-print-directory -s install B="$build" PREFIX="$prefix" >/dev/null
cat > "$prefix/use.c" <<'C'
#include <stdio.h>
#include <stray/photometry_io.h>
int main(void)
{
	struct stray_fluxes f;
	struct stray_error err;

	stray_error_clear(&err);
	if (stray_reference_fluxes(stray_sensor_st16_like(), &f, &err))
		return 1;
	printf("%.4e\n", f.sun);
	return f.sun > 1e20 ? 0 : 1;
}
C
export PKG_CONFIG_PATH="$prefix/lib/pkgconfig"
cc -std=c99 -o "$prefix/use" "$prefix/use.c" $(pkg-config --cflags --libs --static stray)
sun=$("$prefix/use")
[ -x "$prefix/bin/stray" ] || { echo "check-install: stray not installed"; exit 1; }
echo "check-install: installed under a scratch prefix, pkg-config stray links (F_sun $sun)"
