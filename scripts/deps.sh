#!/bin/sh
# deps.sh PURPOSE: make sure the Debian packages PURPOSE needs are present.
# As root on Debian it installs what is missing (apt-get update first);
# otherwise it prints the exact apt-get line and fails.
set -u
purpose=${1:-build}
case $purpose in
build) pkgs="gcc make pkg-config libpng-dev zlib1g-dev" ;;
check) pkgs="libpng-dev zlib1g-dev python3 time plotutils" ;;
bench) pkgs="plotutils povray python3-contourpy python3-numpy time imagemagick qhull-bin" ;;
fuzz) pkgs="clang libclang-rt-14-dev" ;;
*) echo "deps.sh: unknown purpose '$purpose'" >&2; exit 64 ;;
esac
# Each part of the project may list more packages in scripts/deps.d/PART.txt, one line per
# purpose: "PURPOSE package package ..." (# starts a comment).
for f in scripts/deps.d/*.txt; do
	[ -f "$f" ] || continue
	more=$(awk -v p="$purpose" '$1 == p { for (k = 2; k <= NF; k++) print $k }' "$f" | sed 's/#.*//')
	pkgs="$pkgs $more"
done
missing=""
for p in $pkgs; do
	dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed" || missing="$missing $p"
done
[ -z "$missing" ] && exit 0
if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
	echo "deps.sh: installing$missing" >&2
	export DEBIAN_FRONTEND=noninteractive
	apt-get update -qq >&2 && apt-get install -y -qq --no-install-recommends $missing >&2 && exit 0
	echo "deps.sh: apt-get failed for:$missing" >&2
	exit 69
fi
echo "deps.sh: missing Debian packages for '$purpose'. Install them with:" >&2
echo "  sudo apt-get install$missing" >&2
exit 69
