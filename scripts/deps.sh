#!/bin/sh
# deps.sh PURPOSE...: make sure the Debian packages the PURPOSEs need are present.
# As root on Debian it installs what is missing (apt-get update first);
# otherwise it prints the exact apt-get line and fails with 69 (EX_UNAVAILABLE).
# Purposes: build (every program), check (make check; SANITIZE=1 adds asan), bench, fuzz,
# demo, fresh (scripts/fresh-check.sh). The make targets call it before building anything
# that needs the packages.
set -u
cd "$(dirname "$0")/.." || exit 70
[ $# -gt 0 ] || set -- build
pkgs=""
for purpose in "$@"; do
	case $purpose in
	build) more="gcc make pkg-config libpng-dev zlib1g-dev" ;;
	check) more="libpng-dev zlib1g-dev python3 time plotutils" ;;
	asan) more="libasan8 libubsan1" ;;
	bench) more="plotutils povray python3-contourpy python3-numpy time imagemagick qhull-bin" ;;
	fuzz) more="clang libclang-rt-14-dev" ;;
	demo) more="" ;;
	fresh) more="mmdebstrap git" ;;
	*) echo "deps.sh: unknown purpose '$purpose'" >&2; exit 64 ;;
	esac
	pkgs="$pkgs $more"
	# Each part of the project may list more packages in scripts/deps.d/PART.txt, one line per
	# purpose: "PURPOSE package package ..." (# starts a comment).
	for f in scripts/deps.d/*.txt; do
		[ -f "$f" ] || continue
		more=$(sed 's/#.*//' "$f" | awk -v p="$purpose" '$1 == p { for (k = 2; k <= NF; k++) print $k }')
		pkgs="$pkgs $more"
	done
done
missing=""
for p in $pkgs; do
	case " $missing " in *" $p "*) continue ;; esac
	dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed" || missing="$missing $p"
done
[ -z "$missing" ] && exit 0
if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
	echo "deps.sh: installing$missing" >&2
	export DEBIAN_FRONTEND=noninteractive
	apt-get update -qq >&2 && apt-get install -y -qq --no-install-recommends $missing >&2 < /dev/null && exit 0
	echo "deps.sh: apt-get failed for:$missing" >&2
	exit 69
fi
echo "deps.sh: missing Debian packages for '$*'. Install them with:" >&2
echo "  sudo apt-get install --no-install-recommends$missing" >&2
exit 69
