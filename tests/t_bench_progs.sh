# t_bench_progs.sh: the bench's own programs (pixel comparer, contour and Voronoi timers) build clean and measure right.
. tests/lib.sh
: "${TESTBIN:=build/native/tests}"
LIBDIR=$(dirname "$TESTBIN")
SAN=""
[ "${SANITIZE:-}" = 1 ] && SAN="-fsanitize=address,undefined -fno-omit-frame-pointer"
CFL="-std=c11 -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE -O1 -Wall -Wextra -Werror"
LIBS="$LIBDIR/libcore.a $LIBDIR/libdrivers.a $LIBDIR/libmeta.a $(pkg-config --libs libpng zlib 2>/dev/null) -lpthread -lm"
for p in bench_pixcmp bench_contour bench_voronoi; do
	# shellcheck disable=SC2086
	if ${CC:-cc} $CFL "-DLOCUS_VERSION=\"test\"" $SAN -Imeta -Icore -Idrivers "tests/bench/$p.c" $LIBS -o "$T/$p" 2> "$T/$p.log"; then
		ok "$p builds without warnings"
	else
		notok "$p builds without warnings: $(head -3 "$T/$p.log")"
	fi
done
[ -x "$T/bench_pixcmp" ] && [ -x "$T/bench_contour" ] && [ -x "$T/bench_voronoi" ] || done_tests

# bench_pixcmp on two 4x2 pictures, background (26,26,38) as in the bench views. B differs in
# pixel 1 by one level (object in both), in pixel 2 (background in A, object in B: one
# silhouette pixel); A has a comment in its header, as POV-Ray writes one.
bg='\032\032\046'
printf "P6\n# Software: a test\n4 2\n255\n$bg\310\144\062$bg$bg$bg$bg$bg$bg" > "$T/a.ppm"
printf "P6\n4 2\n255\n$bg\311\144\062\012\012\012$bg$bg$bg$bg$bg" > "$T/b.ppm"
"$T/bench_pixcmp" "$T/a.ppm" "$T/b.ppm" > "$T/ab.out" 2>&1
# squared differences 1 + 16^2 + 16^2 + 28^2 = 1297 over 24 samples: 10 log10(255^2 * 24 / 1297)
echo "psnr_db=30.80 silhouette_px=1 diff_px=2 max_diff=28" > "$T/ab.want"
same_file "PSNR, silhouette, differing pixels and largest difference of a known pair" "$T/ab.want" "$T/ab.out"
"$T/bench_pixcmp" "$T/a.ppm" "$T/a.ppm" > "$T/aa.out" 2>&1
echo "psnr_db=inf silhouette_px=0 diff_px=0 max_diff=0" > "$T/aa.want"
same_file "identical pictures: PSNR inf" "$T/aa.want" "$T/aa.out"
"$T/bench_pixcmp" -b 1,2,3 "$T/a.ppm" "$T/b.ppm" > "$T/b123.out" 2>&1
grep -q ' silhouette_px=0 ' "$T/b123.out" && ok "-b sets the background colour" ||
	notok "-b 1,2,3 should leave no silhouette pixels: $(cat "$T/b123.out")"
printf "P6\n2 2\n255\n$bg$bg$bg$bg" > "$T/small.ppm"
printf "P6\n4 2\n255\n$bg$bg" > "$T/short.ppm"
printf "P6\n4 2\n65535\n" > "$T/deep.ppm"
expect_exit 65 "pictures of different sizes are bad data" "$T/bench_pixcmp" "$T/a.ppm" "$T/small.ppm"
expect_exit 65 "truncated pixel data is bad data" "$T/bench_pixcmp" "$T/a.ppm" "$T/short.ppm"
expect_exit 65 "16-bit PPM is refused" "$T/bench_pixcmp" "$T/a.ppm" "$T/deep.ppm"
expect_exit 65 "a text file is not a PPM" "$T/bench_pixcmp" fixtures/bench/trifocal.pov "$T/a.ppm"
expect_exit 66 "missing file" "$T/bench_pixcmp" "$T/a.ppm" "$T/none.ppm"
expect_exit 64 "one picture is a usage error" "$T/bench_pixcmp" "$T/a.ppm"
expect_exit 64 "bad -b is a usage error" "$T/bench_pixcmp" -b 1,2 "$T/a.ppm" "$T/b.ppm"

# the shared options of the timing programs (tests/bench/bench_util.h)
for p in bench_pixcmp bench_contour bench_voronoi; do
	"$T/$p" --version > "$T/v.out" 2>&1
	grep -q "^$p test$" "$T/v.out" && ok "$p --version" || notok "$p --version: $(cat "$T/v.out")"
	check "$p --help" "$T/$p" --help
done
for p in bench_contour bench_voronoi; do
	expect_exit 64 "$p -n 0 is a usage error" "$T/$p" -n 0
	expect_exit 64 "$p: unknown argument" "$T/$p" --frobnicate
	expect_exit 74 "$p: unwritable output" "$T/$p" -n 1 -o "$T/no/such/dir.meta"
	"$T/$p" -n 1 -o "$T/$p.meta" > "$T/$p.out" 2>&1
	grep -q "^BENCH ${p#bench_}-locus [0-9.]* s " "$T/$p.out" && ok "$p prints its BENCH line" ||
		notok "$p BENCH line: $(tail -1 "$T/$p.out")"
	check "$p -o writes a valid meta file" "$BIN/locus-meta" check "$T/$p.meta"
	[ ! -e "$T/$p.meta.tmp" ] && ok "$p leaves no temporary file" || notok "$p left $p.meta.tmp"
done
# the workload's counts (also what contourpy finds: docs/benchmarks.md)
grep -q ' segments=41973 polylines=34 ' "$T/bench_contour.out" && ok "contour: 41,973 segments in 34 polylines" ||
	notok "contour counts changed: $(tail -1 "$T/bench_contour.out")"
done_tests
