#!/bin/sh
# t_film_skip.sh: locus-film --skip-existing (docs/farm.md): with a frame pattern, a frame whose
# file is there and whole is left alone (not even rewritten), the others are made, and the
# sequence equals the one a single run writes, byte for byte (SOURCE_DATE_EPOCH fixed): DPX,
# Cineon and RLE; a truncated file, a file of another frame under the name, and a file that is
# not a frame are made again, each named on stderr; all there: nothing made.
. tests/lib.sh
R="$BIN/locus-render"
F="$BIN/locus-film"
export SOURCE_DATE_EPOCH=1700000000
printf 'view\n  eye 0 1 -6\n  size 40 30\nend\nlight point 3 6 -5\nobject a\n  point -1+0.2*t 0 0 weight 1+0.1*t\n  point 1 0 0\n  point 0 1.2 0.3\n  c 3.4+0.05*t\nend\n' > "$T/anim.scene"
"$R" "$T/anim.scene" --frames 2-9 -o "$T/anim.meta" --quiet || notok "locus-render --frames 2-9 failed"

# same_dir DESC A B: the same file names in A and B, each byte-identical
same_dir() {
	if [ "$(ls -A "$2")" = "$(ls -A "$3")" ] && (for f in "$2"/*; do cmp -s "$f" "$3/${f##*/}" || exit 1; done); then
		ok "$1"
	else
		notok "$1: $(ls -A "$3" | tr '\n' ' ')"
	fi
}
for ext in dpx cin rle; do
	rm -rf "$T/ref" "$T/sk"; mkdir "$T/ref" "$T/sk"
	"$F" --size 48x32 "$T/anim.meta" -o "$T/ref/f-%04d.$ext" || notok "$ext: the single run failed"
	# frames 2..9: 2, 3 and 4 there, 5 cut in half, 6 holds frame 2 (DPX, Cineon; an RLE file
	# has no frame number to tell), 8 is not a frame; 7 and 9 missing
	cp "$T/ref/f-0002.$ext" "$T/ref/f-0003.$ext" "$T/ref/f-0004.$ext" "$T/sk/"
	head -c $(($(wc -c < "$T/ref/f-0005.$ext") / 2)) "$T/ref/f-0005.$ext" > "$T/sk/f-0005.$ext"
	[ $ext = rle ] || cp "$T/ref/f-0002.$ext" "$T/sk/f-0006.$ext"
	echo junk > "$T/sk/f-0008.$ext"
	touch -d 2000-01-01 "$T/sk/f-0003.$ext"
	"$F" --size 48x32 "$T/anim.meta" -o "$T/sk/f-%04d.$ext" --skip-existing 2> "$T/err"; rc=$?
	[ $rc = 0 ] || notok "$ext: --skip-existing exit $rc: $(cat "$T/err")"
	same_dir "$ext: --skip-existing over a partial sequence gives the single run's files" "$T/ref" "$T/sk"
	[ "$(date -r "$T/sk/f-0003.$ext" +%Y)" = 2000 ] && ok "$ext: a whole frame's file is left untouched" ||
		notok "$ext: f-0003.$ext was rewritten"
	grep -q "frame 5: .*f-0005.$ext: .*made again" "$T/err" && grep -q "frame 8: .*f-0008.$ext: .*made again" "$T/err" &&
		grep -q "3 of 8 frames were there and whole, 5 made" "$T/err" &&
		ok "$ext: the cut-short and the foreign file are named, and the count said" || notok "$ext: stderr: $(cat "$T/err")"
	case $ext in
	rle) ;;   # RLE carries no frame number
	*) grep -q "frame 6: .*holds frame 2, not frame 6" "$T/err" && ok "$ext: a file of frame 2 under frame 6's name is made again" ||
		notok "$ext: frame 6: $(cat "$T/err")" ;;
	esac
	ls -A "$T/sk" | grep -q -v "^f-000[2-9]\.$ext\$" && notok "$ext: left behind: $(ls -A "$T/sk")" || ok "$ext: no temporary left beside the frames"
	"$F" --size 48x32 "$T/anim.meta" -o "$T/sk/f-%04d.$ext" --skip-existing 2> "$T/err"
	grep -q "8 of 8 frames were there and whole, 0 made" "$T/err" && ok "$ext: a rerun over the whole sequence makes nothing" ||
		notok "$ext: rerun: $(cat "$T/err")"
done
# per-frame files (one page each, as a farm's tasks write them): frame 4 there, the rest made
rm -rf "$T/pf" "$T/one"; mkdir "$T/pf" "$T/one"
"$R" "$T/anim.scene" --frames 2-9 -o "$T/pf/m-%04d.meta" --quiet
"$F" --size 48x32 "$T/pf/m-0004.meta" -o "$T/one/f-%04d.dpx"
for m in "$T"/pf/m-*.meta; do "$F" --size 48x32 "$m" -o "$T/one/f-%04d.dpx" --skip-existing 2>> "$T/err1" || notok "$m: exit $?"; done
"$F" --size 48x32 "$T/anim.meta" -o "$T/ref/g-%04d.dpx"
for k in 2 3 4 5 6 7 8 9; do cmp -s "$T/one/f-000$k.dpx" "$T/ref/g-000$k.dpx" || notok "per-frame input: frame $k differs"; done
[ "$(grep -c 'were there and whole' "$T/err1")" = 8 ] && grep -q "1 of 1 frames were there and whole, 0 made" "$T/err1" &&
	ok "per-frame inputs: the frame there skipped, the 7 others equal the single run's" || notok "per-frame: $(cat "$T/err1")"
expect_exit 64 "--skip-existing without a frame pattern is refused" "$F" --size 48x32 "$T/anim.meta" -o "$T/x.dpx" --skip-existing
expect_exit 64 "--skip-existing from stdin is refused" sh -c "'$F' --size 48x32 --skip-existing -o '$T/y-%04d.dpx' < '$T/anim.meta'"
done_tests
