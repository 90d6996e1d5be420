#!/bin/sh
# fresh-check.sh: the README's two commands on a fresh Debian 12 machine, as a new user meets them.
#
# Builds a minimal Debian 12 root (mmdebstrap --variant=apt: apt, git, ca-certificates, make, gcc
# and nothing else), gives it this machine's apt sources, clones the committed HEAD of the
# repository this script lives in, lays a read-only copy of ../shared beside the clone as CI does,
# puts a stand-in `convert` first on PATH (it handles PNG only, as the base image's does when
# ImageMagick is absent), and runs as root in a chroot, with no standard input:
#     make demo; make check; then make check again with ../shared removed.
# Prints each command's exit status, its time and the test summary line; exits 1 if any failed,
# 69 if its own needs (mmdebstrap: scripts/deps.sh fresh) are missing. Everything happens in a
# mktemp directory (FRESH_KEEP=1 keeps it); mounts are undone on every exit path.
{ # the whole script is read before it runs: editing the file meanwhile cannot change this run
set -u
here=$(cd "$(dirname "$0")" && pwd)
repo=$(git -C "$here" rev-parse --show-toplevel) || exit 70
head=$(git -C "$repo" rev-parse HEAD) || exit 70
shared=$(cd "$repo/.." && pwd)/shared
(cd "$repo" && scripts/deps.sh fresh) || exit 69
[ "$(id -u)" = 0 ] || { echo "fresh-check.sh: chroot and mounts need root" >&2; exit 77; }

W=$(mktemp -d "${TMPDIR:-/var/tmp}/locus-fresh.XXXXXX") || exit 73
root=$W/root
mounted=""
cleanup() {
	rc=$?
	trap - EXIT INT TERM HUP
	ok=1
	for m in $mounted; do   # in reverse order of mounting (the list is built front-first)
		umount "$root/$m" 2>/dev/null || umount -l "$root/$m" 2>/dev/null || { ok=0; echo "fresh-check.sh: cannot unmount $root/$m" >&2; }
	done
	if [ "$ok" = 1 ] && [ "${FRESH_KEEP:-0}" != 1 ]; then
		rm -rf --one-file-system "$W"
	else
		echo "fresh-check.sh: left $W" >&2
	fi
	exit "$rc"
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM
trap 'exit 129' HUP

now() { date +%s; }
elapsed() { s=$(( $(now) - $1 )); printf '%dm%02ds' $((s / 60)) $((s % 60)); }

# installed: the root's Debian packages, and their installed size in MB
installed() {
	dpkg-query --admindir="$root/var/lib/dpkg" -W -f '${db:Status-Abbrev} ${Installed-Size}\n' 2>/dev/null |
		awk '$1 == "ii" { n++; kb += $2 } END { printf "%d packages, %d MB", n, kb / 1024 }'
}

# The host's apt sources, as mmdebstrap arguments (it writes them into the root): the one-line
# sources.list, *.list files and deb822 *.sources files that apt itself would read.
set --
for f in /etc/apt/sources.list /etc/apt/sources.list.d/*.list /etc/apt/sources.list.d/*.sources; do
	[ -s "$f" ] || continue
	grep -q '^[[:space:]]*[^#[:space:]]' "$f" || continue
	set -- "$@" "$f"
done
echo "fresh-check: apt sources: ${*:-the default mirror of mmdebstrap}"

t0=$(now)
echo "fresh-check: mmdebstrap bookworm into $root"
if ! mmdebstrap --quiet --variant=apt --include=git,ca-certificates,make,gcc bookworm "$root" "$@"; then
	echo "fresh-check: mmdebstrap failed"
	exit 1
fi
echo "fresh-check: root made in $(elapsed "$t0"): $(installed)"

# The stand-in convert: reads a PNG only, as the base image's stand-in does when ImageMagick is
# absent (with ImageMagick installed it hands every call to it, as the base image's does).
mkdir -p "$root/usr/local/bin"
cat > "$root/usr/local/bin/convert" <<'EOF'
#!/bin/sh
# stand-in for ImageMagick's convert (scripts/fresh-check.sh): PNG in, PNG out, nothing else
[ -x /usr/bin/convert ] && exec /usr/bin/convert "$@"
for a in "$@"; do
	case $a in -*) continue ;; esac
	if [ -f "$a" ] && [ "$(head -c 8 "$a" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ]; then
		out=$(eval "echo \${$#}")
		[ "$out" != "$a" ] && cp "$a" "$out" && exit 0
	fi
	echo "convert (stand-in): cannot read $a: only PNG" >&2
	exit 1
done
echo "convert (stand-in): no input" >&2
exit 1
EOF
chmod 755 "$root/usr/local/bin/convert"

# The clone and ../shared beside it, as CI lays them: the project at /build/locus, the shared
# material at /build/shared without write bits.
mkdir -p "$root/build"
git clone -q --no-checkout "$repo" "$root/build/locus" && git -C "$root/build/locus" checkout -q -B fresh "$head" || exit 1
echo "fresh-check: cloned $head"
if [ -d "$shared" ]; then
	cp -a "$shared" "$root/build/shared" && chmod -R a-w "$root/build/shared" || exit 1
else
	echo "fresh-check: no ../shared beside the repository; the first make check runs without it"
fi

for m in proc sys dev dev/pts; do
	mkdir -p "$root/$m"
	mount --bind "/$m" "$root/$m" || exit 1
	mounted="$m $mounted"
done

# run NAME COMMAND: one command in the root as root, in the clone, with no standard input
fails=0
report=""
run() {
	name=$1; shift
	log=$W/$(echo "$name" | tr ' /' '__').log
	echo "fresh-check: == $name"
	t=$(now)
	{
		chroot "$root" /usr/bin/env -i PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
			HOME=/root LANG=C.UTF-8 TERM=dumb sh -c "cd /build/locus && $*" < /dev/null 2>&1
		echo $? > "$log.rc"
	} | tee "$log"
	rc=$(cat "$log.rc")
	sum=$(grep -E '^[0-9]+ passed, [0-9]+ failed, [0-9]+ skipped$' "$log" | tail -n 1)
	grep '^SKIP ' "$log" | sed "s/^/fresh-check: $name: /"
	line="$name: exit $rc, $(elapsed "$t")${sum:+, $sum}; root now $(installed)"
	echo "fresh-check: $line"
	report="$report$line
"
	[ "$rc" = 0 ] || fails=$((fails + 1))
}
run "make demo" make demo
run "make check" make check
if [ -d "$root/build/shared" ]; then
	chmod -R u+w "$root/build/shared" && rm -rf "$root/build/shared"
fi
run "make check without ../shared" make check
deb=$(cat "$root/etc/debian_version")
cores=$(nproc)
total=$(elapsed "$t0")
echo "fresh-check: summary: Debian $deb, $cores cores, $total in all"
printf '%s' "$report" | sed 's/^/fresh-check:   /'
[ "$fails" = 0 ] || { echo "fresh-check: $fails of the commands failed"; exit 1; }
echo "fresh-check: all passed"
exit 0
}
