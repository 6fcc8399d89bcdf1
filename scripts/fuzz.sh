#!/usr/bin/env bash
# Run libFuzzer targets, JOBS at a time, and print executions and crashes
# per target in one table.
#
#   scripts/fuzz.sh ci   SECONDS RUNS JOBS build/fuzz/fuzz_x ...
#   scripts/fuzz.sh long SECONDS RUNS JOBS build/fuzz/fuzz_x ...
#   scripts/fuzz.sh merge build/fuzz/fuzz_x ...
#
# Each target X reads tests/fuzz/corpus/X (the kept, minimised corpus) and
# tests/fuzz/seeds/X (hand-written seeds); neither is ever written.  New
# inputs go to a scratch folder: build/fuzz/ci-X (emptied first) in `ci`
# mode, build/fuzz/corpus-X (kept between runs, for `make fuzz-merge`) in
# `long` mode.  A target stops at SECONDS (0: no limit) or RUNS (0: no
# limit), whichever comes first, or at its first crash; crash, leak,
# timeout and out-of-memory inputs land in build/fuzz/artifacts/.  Exit 1
# when any target crashed (its report is printed), else 0.
# Before it mutates anything libFuzzer runs every file of the corpus and
# seed folders once (its "#N INITED" line), whatever SECONDS is: a target
# whose log shows fewer than the files it was given is counted as failed
# ("replay"), so even a short box (`make test`: FUZZ_CI_SECONDS) replays
# every kept input, the regressions of issue 14 among them.
# `merge` rewrites tests/fuzz/corpus/X as the inputs of the kept corpus and
# of build/fuzz/corpus-X that add coverage beyond the seeds (-merge=1).
set -u

if [ "$1" = merge ]; then
	shift
	for bin in "$@"; do
		name=$(basename "$bin") short=${name#fuzz_}
		keep=tests/fuzz/corpus/$short seeds=tests/fuzz/seeds/$short
		tmp=build/fuzz/merge-$short
		rm -rf "$tmp" && mkdir -p "$tmp" "$keep" "build/fuzz/corpus-$short"
		[ -d "$seeds" ] && cp "$seeds"/* "$tmp"/
		"$bin" -merge=1 "$tmp" "$keep" "build/fuzz/corpus-$short" \
			>"build/fuzz/$name.merge.log" 2>&1 ||
			{ tail -n 20 "build/fuzz/$name.merge.log"; exit 1; }
		[ -d "$seeds" ] && (cd "$seeds" && for f in *; do rm -f "../../../../$tmp/$f"; done)
		rm -rf "$keep" && mv "$tmp" "$keep"
		echo "$name: $(ls "$keep" | wc -l) files, $(cat "$keep"/* 2>/dev/null | wc -c) bytes beyond the seeds"
	done
	exit 0
fi

mode=$1 secs=$2 runs=$3 jobs=$4
# Leaks inside third-party libraries are theirs, as in the tests: assimp 5.2
# keeps heap blocks when an import fails (tests/lsan.supp).
export LSAN_OPTIONS="suppressions=$(pwd)/tests/lsan.supp:print_suppressions=0"
shift 4
out=build/fuzz
mkdir -p "$out/artifacts" "$out/results"

one() {	# one target; writes $out/results/NAME
	local bin=$1 name short scratch log dirs=() opts=()
	name=$(basename "$bin")
	short=${name#fuzz_}
	log=$out/$name.log
	if [ "$mode" = ci ]; then
		scratch=$out/ci-$short
		rm -rf "$scratch"
	else
		scratch=$out/corpus-$short
	fi
	mkdir -p "$scratch"
	for d in tests/fuzz/corpus/$short tests/fuzz/seeds/$short; do
		[ -d "$d" ] && dirs+=("$d")
	done
	rm -f "$out/artifacts/$name-"*
	[ "$secs" -gt 0 ] && opts+=("-max_total_time=$secs")
	[ "$runs" -gt 0 ] && opts+=("-runs=$runs")
	local t0 t1 rc execs crashes files inited
	files=0
	for d in "${dirs[@]}"; do files=$((files + $(find "$d" -type f | wc -l))); done
	t0=$(date +%s)
	# assimp (C++, no frame pointers) is seen by the suppression only
	# through the slow unwinder; the fast one stops at operator new.
	case $name in
	fuzz_scene_json|fuzz_mesh_file)
		local -x ASAN_OPTIONS=fast_unwind_on_malloc=0 ;;
	esac
	"$bin" "${opts[@]}" -print_final_stats=1 -timeout=10 \
		-rss_limit_mb=2048 -artifact_prefix="$out/artifacts/$name-" \
		"$scratch" "${dirs[@]}" >"$log" 2>&1
	rc=$?
	t1=$(date +%s)
	execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
	[ -n "$execs" ] || execs=$(grep -oE '^#[0-9]+' "$log" | tail -n 1 | tr -d '#')
	crashes=$(ls "$out/artifacts/$name-"{crash,leak,timeout,oom}-* 2>/dev/null | wc -l)
	[ "$rc" -ne 0 ] && [ "$crashes" -eq 0 ] && crashes=1	# died without an artifact
	# every kept file run once: "#N INITED", N counting the empty input
	inited=$(sed -n 's/^#\([0-9]*\)[[:space:]]*INITED.*/\1/p' "$log" | head -n 1)
	echo "$name ${execs:-0} $((t1 - t0)) $crashes $rc $files ${inited:-0}" \
		>"$out/results/$name"
}

if [ "$mode" = one ]; then	# internal: xargs calls back here
	mode=$secs secs=$runs runs=$jobs
	one "$1"
	exit 0
fi

for b in "$@"; do rm -f "$out/results/$(basename "$b")"; done
start=$(date +%s)
printf '%s\n' "$@" | xargs -P "$jobs" -n 1 "$0" one "$mode" "$secs" "$runs"

fail=0
printf '%-22s %12s %6s %10s %8s %8s\n' target executions secs exec/s \
	crashes replayed
for b in "$@"; do
	name=$(basename "$b")
	if ! read -r _ execs t crashes rc files inited <"$out/results/$name"; then
		echo "$name: no result" && fail=1 && continue
	fi
	printf '%-22s %12s %6s %10s %8s %8s\n' "$name" "$execs" "$t" \
		"$((execs / (t > 0 ? t : 1)))" "$crashes" "$inited/$files"
	[ "$crashes" -ne 0 ] && fail=1
	if [ "$crashes" -eq 0 ] && [ "$inited" -lt "$files" ]; then
		echo "$name: replayed $inited of its $files kept inputs" && fail=1
	fi
done
echo "fuzz: $# targets in $(( $(date +%s) - start )) s wall time, $jobs at a time"
for b in "$@"; do
	name=$(basename "$b")
	read -r _ _ _ crashes _ <"$out/results/$name" 2>/dev/null || continue
	[ "$crashes" -eq 0 ] && continue
	echo "== $name: $(ls "$out/artifacts/$name-"* 2>/dev/null | tr '\n' ' ')"
	grep -m 1 -A 25 -E '==ERROR|^ERROR|runtime error|deadly signal' \
		"$out/$name.log"
done
exit $fail
