#!/bin/sh
# run.sh: run each libFuzzer harness of build/fuzz/ for FUZZ_SECONDS (default 60) over its seed
# corpora; new inputs go to build/fuzz/corpus/HARNESS, a crash or hang to build/fuzz/crash/.
# Exits non-zero when any harness found something (libFuzzer's own status). FUZZ_ONLY=NAME runs one;
# FUZZ_B=DIR runs the harnesses built there (e.g. without the guards, see tests/mk/fuzz.mk).
set -u
: "${FUZZ_SECONDS:=60}" "${FUZZ_ONLY:=}"
B=${FUZZ_B:-build/fuzz}
seeds() {
	case $1 in
	meta_text) echo fixtures/meta fixtures/bad fixtures/raster/inputs fixtures/fuzz/meta_text fixtures/fuzz/raster ;;
	meta_binary) echo fixtures/fuzz/meta_binary fixtures/bad ;;
	raster) echo fixtures/fuzz/raster fixtures/meta ;;
	scene) echo fixtures/fuzz/scene fixtures/scenes fixtures/render ;;
	image) echo fixtures/fuzz/image fixtures/raster ;;
	hpgl) echo fixtures/fuzz/hpgl fixtures/hpgl ../shared/corpus/hpgl ;;
	plotmeta) echo fixtures/fuzz/plotmeta fixtures/import ;;
	imgread) echo fixtures/fuzz/imgread ;;
	vector) echo fixtures/meta fixtures/fuzz/raster fixtures/raster/inputs ;;
	vecdash) echo fixtures/dash fixtures/fuzz/vecdash fixtures/meta ;;
	resume) echo fixtures/fuzz/resume ;;
	journal) echo fixtures/fuzz/journal ;;
	svg) echo fixtures/fuzz/svg ../shared/corpus/svg/vpype/misc ;;
	esac
}
# libFuzzer reads every regular file of a corpus directory: give it only the inputs
corpus_of() {
	d=$B/seeds/$1
	rm -rf "$d" && mkdir -p "$d"
	for s in $(seeds "$1"); do
		for f in "$s"/*; do
			[ -f "$f" ] || continue
			case $1 in
			hpgl|plotmeta|imgread|resume|journal|svg)   # every input file (the corpus is copied into build/ only)
				case $f in *.md|*/goldens.txt|*.meta) continue ;; esac
				cp "$f" "$d/$(echo "$s" | tr /. __)_$(basename "$f")"; continue ;;
			esac
			case $f in *.md|*.txt|*.png|*.ppm|*.rle) [ "$1" = image ] || continue ;; esac
			case $f in *.meta|*.lmb|*.scene|*.png|*.ppm|*.rle|*.bin) cp "$f" "$d/$(echo "$s" | tr / _)_$(basename "$f")" ;; esac
		done
	done
	echo "$d"
}
status=0
for h in meta_text meta_binary raster scene image hpgl plotmeta imgread vector vecdash resume journal svg; do
	[ -z "$FUZZ_ONLY" ] || [ "$FUZZ_ONLY" = "$h" ] || continue
	mkdir -p "$B/corpus/$h" "$B/crash"
	s=$(corpus_of "$h")
	log=$B/$h.log
	echo "fuzz: $h for $FUZZ_SECONDS s (log $log)"
	"$B/fuzz_$h" -max_total_time="$FUZZ_SECONDS" -timeout=10 -rss_limit_mb=2048 -max_len=16384 \
		-print_final_stats=1 -artifact_prefix="$B/crash/$h-" "$B/corpus/$h" "$s" > "$log" 2>&1
	rc=$?
	runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
	cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1)
	if [ "$rc" = 0 ]; then
		echo "fuzz: $h: ${runs:-?} executions, $cov, nothing found"
	else
		status=1
		echo "fuzz: $h: FOUND something after ${runs:-?} executions (exit $rc):"
		grep -E '^==[0-9]+==|SUMMARY|assertion failed|Test unit written|ALARM|timeout' "$log" | head -8 | sed 's/^/    /'
	fi
done
exit $status
