# diff.sh: bench group "diff" (sourced by scripts/bench.sh): locus-diff comparing two 4096x3072
# PNGs of the F that differ in one stroke, against ImageMagick's `compare -metric AE` (the count of
# differing pixels) on the same pair, in the same run. Time, CPU and peak RSS (docs/benchmarks.md).

# diff_scale IN OUT CHANGE: the F's drawing times 25.6 on a 4096 x 3072 page (CHANGE=1: the green
# bar 10 units longer)
diff_scale() {
	python3 - "$1" "$2" "$3" <<'PY'
import sys
out = []
for l in open(sys.argv[1]):
    w = l.split()
    if sys.argv[3] == '1' and w[:3] == ['draw', '100', '92']:
        w = ['draw', '110', '92']
    if w and w[0] == 'page':
        out.append('page 4096 3072\n')
    elif w and w[0] == 'size':
        continue
    elif w and w[0] in ('move', 'draw', 'width'):
        out.append(' '.join([w[0]] + [str(round(float(v) * 25.6, 3)) for v in w[1:]]) + '\n')
    elif w and w[0] == 'span':
        out.append('span %d %d %d %s\n' % tuple([int(float(v) * 25.6) for v in w[1:4]] + [w[4]]))
    else:
        out.append(l)
open(sys.argv[2], 'w').writelines(out)
PY
}

bench_diff() {
	if ! have_bin locus-diff || ! have_bin locus-raster; then
		skip diff-png "$BIN/locus-diff or locus-raster not built yet"; return
	fi
	DIFF_IM=$(command -v compare-im6.q16 || command -v compare) ||
		{ fail diff-png "ImageMagick compare missing (Debian imagemagick)"; return; }
	if ! diff_scale fixtures/meta/f-test.meta "$W/diff-a.meta" 0 || ! diff_scale fixtures/meta/f-test.meta "$W/diff-b.meta" 1 ||
			! "$BIN/locus-raster" "$W/diff-a.meta" -o "$W/diff-a.png" 2> "$W/err" ||
			! "$BIN/locus-raster" "$W/diff-b.meta" -o "$W/diff-b.png" 2>> "$W/err"; then
		fail diff-png "the inputs: $(tail -1 "$W/err")"; return
	fi
	# locus-diff exits 1 (they differ): wrapped so that measure sees success
	measure "$BENCH_RUNS" "$W/diff.out" sh -c '"$0" "$1" "$2"; [ $? = 1 ]' "$BIN/locus-diff" "$W/diff-a.png" "$W/diff-b.png" ||
		{ fail diff-png "locus-diff: $M_ERR"; return; }
	ls=$M_S lm=$M_MIB lc=$M_CPU
	npix=$(sed -n 's/.*: \([0-9]*\) of .*/\1/p' "$W/diff.out")
	# compare prints the count on stderr and exits 1 when they differ
	measure "$BENCH_RUNS" /dev/null sh -c '"$0" -metric AE "$1" "$2" null: 2> "$3"; [ $? = 1 ]' \
		"$DIFF_IM" "$W/diff-a.png" "$W/diff-b.png" "$W/im.out" || { fail diff-png "compare: $M_ERR"; return; }
	line diff-png "$ls" imagemagick-compare "$M_S" "$lm" "$M_MIB" "picture=4096x3072" \
		"locus_differing=$npix anchor_differing=$(tr -dc '0-9' < "$W/im.out")" "$(cpu "$lc" "$M_CPU")"
	rm -f "$W/diff-a.png" "$W/diff-b.png"
}
