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
# the static library (libstray.a named, as the shared one is found first)
cc -std=c99 -o "$prefix/use" "$prefix/use.c" $(pkg-config --cflags stray) \
	"$prefix/lib/libstray.a" $(pkg-config --libs --static stray | sed 's/-lstray\b//')
sun=$("$prefix/use")
[ -x "$prefix/bin/stray" ] || { echo "check-install: stray not installed"; exit 1; }
# the shared ones (issue 32): libstray, and the commands' flat calls
cc -std=c99 -o "$prefix/use_so" "$prefix/use.c" $(pkg-config --cflags --libs stray) \
	-Wl,-rpath,"$prefix/lib"
[ "$("$prefix/use_so")" = "$sun" ] || { echo "check-install: shared libstray differs"; exit 1; }
cat > "$prefix/api.c" <<'C'
#include <stdio.h>
#include <straycmd/api.h>
int main(void)
{
	struct stray_api_result *r;
	int rc = stray_api_run("photometry", "{\"sensor\": \"st16-like\"}", &r);

	rc = rc == 0 && stray_api_json(r) ? 0 : 1;
	stray_api_result_free(r);
	return rc;
}
C
cc -std=c99 -o "$prefix/api" "$prefix/api.c" $(pkg-config --cflags --libs straycmd) \
	-Wl,-rpath,"$prefix/lib"
"$prefix/api" || { echo "check-install: libstraycmd's stray_api_run failed"; exit 1; }
so=$(readlink "$prefix/lib/libstray.so.0")
echo "check-install: installed under a scratch prefix, pkg-config stray links static and shared ($so, F_sun $sun), straycmd runs a command"
