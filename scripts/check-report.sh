#!/usr/bin/env bash
# Open a report in headless Chromium as a reader would: screenshot it and
# check that every figure loaded.  With --complete, also require that no
# section is empty.  Usage: scripts/check-report.sh DIR [--complete]
set -eu
dir=$(cd "$1" && pwd); complete=${2:-}
chrome=$(command -v chromium || command -v chromium-browser || true)
[ -n "$chrome" ] || { echo "check-report: chromium is not installed"; exit 1; }
flags=(--headless --no-sandbox --disable-gpu --disable-quic --no-first-run
       --disable-background-networking --disable-component-update --disable-sync)
profile=$(mktemp -d); trap 'rm -rf "$profile"' EXIT
url="file://$dir/report.html"
body=$(timeout 120 "$chrome" "${flags[@]}" --user-data-dir="$profile" \
	--virtual-time-budget=5000 --dump-dom "$url" 2>/dev/null | grep -o '<body[^>]*>' || true)
timeout 120 "$chrome" "${flags[@]}" --user-data-dir="$profile" \
	--window-size=1200,4000 --screenshot="$dir/report_screenshot.png" "$url" \
	>/dev/null 2>&1
figures=$(echo "$body" | sed -n 's/.*data-figures="\([0-9]*\)".*/\1/p')
broken=$(echo "$body" | sed -n 's/.*data-broken="\([0-9]*\)".*/\1/p')
empty=$(grep -c 'class="empty"' "$dir/report.html" || true)
[ -s "$dir/report_screenshot.png" ] || { echo "check-report: no screenshot"; exit 1; }
if [ -z "$figures" ] || [ "$broken" != 0 ] || [ "$figures" -lt 1 ]; then
	echo "check-report: $url: figures '${figures:-?}', broken '${broken:-?}'"
	exit 1
fi
if [ "$complete" = --complete ] && [ "$empty" -ne 0 ]; then
	echo "check-report: $url: $empty section(s) empty"
	exit 1
fi
echo "check-report: $figures figures loaded, $empty empty sections; screenshot $dir/report_screenshot.png"
