#!/bin/sh
# fixtures.sh: `make fixtures`: re-record every expected output deliberately, then print through
# locus-diff what changed against the committed goldens (HEAD). Tests never record; this does.
# Look at every changed picture before committing, and give the reason in fixtures/README.md.
set -u
: "${BIN:=bin}" "${TESTBIN:=build/native/tests}"
fail=0
echo "== recording"
for r in fixtures/*/record.sh; do
	echo "-- $r"
	BIN=$BIN sh "$r" > /dev/null || { echo "$r failed"; fail=1; }
done
echo "-- fixtures/hpgl/goldens.txt"
grep -v '^#' fixtures/hpgl/goldens.txt | while IFS='|' read -r name args in; do
	[ -n "$name" ] || continue
	# shellcheck disable=SC2086
	"$BIN/locus-hpgl" $args "$in" -o "fixtures/hpgl/$name" || echo "locus-hpgl $name failed"
done
echo "-- fixtures/import (locus-meta import)"
# every corpus golden there is (FILE.meta for ../shared/corpus/hpgl/FILE); zigzag is ours
for g in fixtures/import/*.meta; do
	f=$(basename "$g" .meta)
	[ "$f" = zigzag ] && continue
	"$BIN/locus-meta" import "../shared/corpus/hpgl/$f" -o "$g" || echo "import $f failed"
done
"$BIN/locus-meta" import fixtures/import/zigzag.plot -o fixtures/import/zigzag.meta || echo "import zigzag failed"
for t in "$TESTBIN"/test_*golden*; do
	[ -x "$t" ] || continue
	echo "-- $t"
	LOCUS_RECORD=1 "$t" > /dev/null || { echo "$t failed"; fail=1; }
done
echo "== what changed (git status of fixtures/, each changed golden through locus-diff -v)"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
changed=0
git status --porcelain -- fixtures | while read -r st path; do
	changed=1
	case $st in
	'??') echo "new: $path (describe it in fixtures/README.md)"; continue ;;
	D) echo "removed: $path"; continue ;;
	esac
	old="$tmp/old.$(basename "$path")"
	new="$tmp/new.$(basename "$path")"
	git show "HEAD:$path" > "$old" 2> /dev/null || { echo "changed: $path (not in HEAD)"; continue; }
	cp "$path" "$new"
	case $path in *.gz) gzip -dc "$old" > "$old.x" && gzip -dc "$new" > "$new.x" && old=$old.x && new=$new.x ;; esac
	echo "changed: $path"
	if "$BIN/locus-diff" -v "$old" "$new" > "$tmp/rep" 2> "$tmp/err"; then
		echo "  (the same picture or drawing: only the bytes changed)"
	fi
	sed 's/^/  /' "$tmp/rep" "$tmp/err" | sed "s|$tmp/old\.|HEAD:|g; s|$tmp/new\.|now:|g"
done
[ -n "$(git status --porcelain -- fixtures)" ] || echo "nothing changed: every golden re-recorded to the same bytes"
exit $fail
