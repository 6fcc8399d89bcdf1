#!/usr/bin/env bash
# The repository stands alone: every page of docs/ that the code, the help
# texts, the scripts or the README point a user to (`docs/NAME.md`, not
# `../shared/docs/...`) exists in the repository.  Fails naming each
# missing page and one place that points to it.
# Usage: scripts/check-docs.sh
set -eu
cd "$(dirname "$0")/.."
missing=0
while read -r page; do
	[ -f "$page" ] && continue
	where=$(grep -rnE --include='*.c' --include='*.h' --include='*.cpp' \
		--include='*.md' --include='*.sh' --include='*.mk' \
		--include=Makefile "(^|[^/a-z])$page" \
		libstray tracer diagnose firmware_fdr rig mission frames tools mpi scripts docs \
		README.md Makefile 2>/dev/null | head -n 1)
	echo "check-docs: $page is missing (named at ${where%%:*}:$(echo "$where" | cut -d: -f2))"
	missing=$((missing + 1))
done < <(grep -rhoE --include='*.c' --include='*.h' --include='*.cpp' \
	--include='*.md' --include='*.sh' --include='*.mk' --include=Makefile \
	"(^|[^/a-z.])docs/[a-z0-9_-]+\.md" \
	libstray tracer diagnose firmware_fdr rig mission frames tools mpi scripts docs \
	README.md Makefile 2>/dev/null | sed -E 's|^[^d]*||' | sort -u)
[ "$missing" -eq 0 ] || exit 1
echo "check-docs: every docs/ page the repository names is in it"
