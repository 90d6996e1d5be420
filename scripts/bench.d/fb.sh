# scripts/bench.d/fb.sh (sourced by scripts/bench.sh): issue 7, the framebuffer devices.
#  - fb-quant-PIC-...: 256-colour quantisation of a 1024x768 24-bit picture (PIC: plate, a
#    rendered gallery plate; plasma, a seeded ImageMagick plasma; photo, the astronaut photograph
#    of python3-skimage), fed to locus-xga as a binary meta file holding the picture as an image
#    and written as an indexed PNG, against pngquant 2.17 (default dithered / --nofs) and
#    ImageMagick -colors 256 (-dither FloydSteinberg / +dither) on the PNG of the same picture.
#    PSNR against the 24-bit original (ImageMagick compare) and whole-program time each.
#    Which rows are the issue's targets (issue_target=yes): the -dac8 rows against pngquant.
#    The issue asks for "PSNR at least pngquant's ... at no more than half its time" of an
#    indexed PNG; pngquant's PNG holds 8-bit palette entries, and so does Locus's with
#    -O dac=8: the same kind of file, dithered against dithered, undithered against --nofs
#    (target: PSNR >= pngquant's and ratio >= 2). The rows without -dac8 are the hardware's
#    6-bit DAC (the framebuffer modes, issue item 4: "at the DAC's 6-bit precision"): no
#    palette of 6-bit entries, of any size, with any dithering, does better than every pixel
#    shown as its nearest 6-bit colour, printed as ceiling_db= (the bound; 44.3 dB on the plate,
#    below pngquant's 59 dB with 8-bit entries). Their target (issue_target=dac6): PSNR at
#    least min(anchor's, ceiling - 0.05 dB) and, against pngquant, ratio >= 2. Against
#    ImageMagick only the PSNR is compared (target=psnr), 6-bit rows with the same ceiling rule.
#  - fb-a-13h, fb-a-xga: workload a (990,000 segments) to mode 13h and XGA as indexed PNG,
#    against locus-raster's PNG of the same file (target: at most 1.3x its time, ratio >= 0.77).

# psnr ORIG PIC: PSNR in dB (ImageMagick), "inf" when identical
fb_psnr() { compare -metric PSNR "$1" "$2" null: 2>&1 | awk '{print $1}'; }

# fb_ceiling PNG: the PSNR (dB) of the picture with every channel shown as its nearest 6-bit DAC
# level ((v << 2) | (v >> 4)): the best any palette of 6-bit entries can do, dithered or not
fb_ceiling() {
	python3 - "$1" <<'EOF'
import math, subprocess, sys
ppm = subprocess.run(["convert", sys.argv[1], "-strip", "-depth", "8", "ppm:-"], capture_output=True, check=True).stdout
fields, pos = [], 0
while len(fields) < 4:                 # P6, width, height, maxval, then one whitespace byte
    while ppm[pos:pos + 1].isspace():
        pos += 1
    end = pos
    while not ppm[end:end + 1].isspace():
        end += 1
    fields.append(ppm[pos:end])
    pos = end
data = ppm[pos + 1:]
levels = [(v << 2) | (v >> 4) for v in range(64)]
err = bytes(min(abs(c - l) for l in levels) for c in range(256))
e = data.translate(err)
se = sum(e.count(bytes([k])) * k * k for k in range(1, 4))
print("inf" if se == 0 else "%.3f" % (10 * math.log10(255.0 * 255.0 * len(data) / se)))
EOF
}

# fb_png2meta PNG OUT: the picture as one image statement (text), then binary
fb_png2meta() {
	python3 - "$1" "$W/fb-img.meta" <<'EOF' || return 1
import subprocess, sys
src, dst = sys.argv[1], sys.argv[2]
ppm = subprocess.run(["convert", src, "-strip", "-depth", "8", "ppm:-"], capture_output=True, check=True).stdout
magic, w, h, mx, data = ppm.split(maxsplit=4)
w, h = int(w), int(h)
out = [f"LOCUS-META 1\npage {w} {h}\nimage 0 0 {w} {h}\n"]
for y in range(h):
    row = data[y * w * 3:(y + 1) * w * 3]
    toks, x = [], 0
    while x < w:
        c, n = row[3 * x:3 * x + 3], 1
        while x + n < w and row[3 * (x + n):3 * (x + n) + 3] == c:
            n += 1
        toks.append(f"{n} #{c.hex()}")
        x += n
    out.append("row " + " ".join(toks) + "\n")
out.append("end-page\n")
open(dst, "w").write("".join(out))
EOF
	"$BIN/locus-meta" convert --binary "$W/fb-img.meta" -o "$2"
}

# fb_pair NAME PIC LOCUS_OPTS ANCHOR ANCHOR_CMD...: rounds of Locus and the anchor, one line.
# Against pngquant the time ratio must be >= 2; against ImageMagick only the PSNR counts. Rows
# with dac=8 in LOCUS_OPTS: PSNR at least the anchor's; the others (6-bit DAC): at least
# min(the anchor's, the 6-bit ceiling - 0.05 dB), with ceiling_db= on the line.
fb_pair() {
	p_n=$1 p_pic=$2 p_opt=$3 p_an=$4
	shift 4
	case $p_an in pngquant*) p_t=2 ;; *) p_t=0 ;; esac
	case $p_opt in *dac=8*) p_c=inf ;; *) eval "p_c=\$fb_ceil_$p_pic" ;; esac
	: > "$W/r.fbl"
	: > "$W/r.fba"
	ERR="" i=0
	while [ "$i" -lt "$SLOW_RUNS" ] && [ -z "$ERR" ]; do
		# shellcheck disable=SC2086
		once fbl /dev/null "$BIN/locus-xga" $p_opt "$W/$p_pic.lmb" -o "$W/$p_n.locus.png"
		once fba /dev/null "$@"
		i=$((i + 1))
	done
	if [ -n "$ERR" ]; then fail "$p_n" "$ERR"; return; fi
	med "$W/r.fba"
	a_s=$M_S a_mib=$M_MIB a_cpu=$M_CPU
	med "$W/r.fbl"
	lp=$(fb_psnr "$W/$p_pic.png" "$W/$p_n.locus.png")
	ap=$(fb_psnr "$W/$p_pic.png" "$W/$p_n.anchor.png")
	r=$(ratio "$a_s" "$M_S")
	good=$(awk -v l="$lp" -v a="$ap" -v r="$r" -v t="$p_t" -v c="$p_c" 'BEGIN {
		want = a + 0; if (c != "inf" && c - 0.05 < want) want = c - 0.05
		print (l + 0 >= want && r + 0 >= t) ? "yes" : "no"}')
	tg=$([ "$p_t" = 2 ] && echo 2 || echo psnr)
	case $p_opt in
	*dac=8*) it=$([ "$p_t" = 2 ] && echo yes || echo no) ceil="" ;;
	*) it=dac6 ceil="ceiling_db=$p_c" ;;
	esac
	line "$p_n" "$M_S" "$p_an" "$a_s" "$M_MIB" "$a_mib" "target=$tg pass=$good issue_target=$it $(cpu "$M_CPU" "$a_cpu")" \
		"locus_psnr_db=$lp anchor_psnr_db=$ap${ceil:+ $ceil} colours=$(identify -format %k "$W/$p_n.locus.png")"
}

bench_fb() {
	if ! have_bin locus-xga || ! have_bin locus-vga || ! have_bin locus-meta; then
		skip fb-quant "$BIN/locus-xga, locus-vga or locus-meta not built yet"; return
	fi
	if ! have pngquant || ! have convert || ! have compare || ! have python3; then
		fail fb-quant "pngquant, imagemagick or python3 missing"; return
	fi
	photo=/usr/lib/python3/dist-packages/skimage/data/astronaut.png
	# the three pictures, 1024x768
	sed 's/^  size 640 480/  size 1024 768/' fixtures/scenes/default.scene > "$W/plate.scene"
	if ! { "$BIN/locus-render" "$W/plate.scene" -o "$W/plate.meta" &&
			"$BIN/locus-raster" "$W/plate.meta" -o "$W/plate.png"; } 2> "$W/fb.log"; then
		fail fb-quant "the gallery plate does not render: $(tail -1 "$W/fb.log")"; return
	fi
	convert -size 1024x768 -seed 7 plasma:fractal "$W/plasma.png"
	pics="plate plasma"
	if [ -f "$photo" ]; then
		convert "$photo" -resize '1024x768^' -gravity center -extent 1024x768 "$W/photo.png"
		pics="$pics photo"
	else
		skip fb-quant-photo "no $photo (Debian python3-skimage)"
	fi
	for p in $pics; do
		if ! fb_png2meta "$W/$p.png" "$W/$p.lmb" 2> "$W/fb.log"; then
			fail "fb-quant-$p" "meta of the picture: $(tail -1 "$W/fb.log")"; continue
		fi
		if ! c=$(fb_ceiling "$W/$p.png" 2> "$W/fb.log"); then
			fail "fb-quant-$p" "the 6-bit ceiling: $(tail -1 "$W/fb.log")"; continue
		fi
		eval "fb_ceil_$p=\$c"
		fb_pair "fb-quant-$p-fs" "$p" "" pngquant \
			pngquant --force --output "$W/fb-quant-$p-fs.anchor.png" 256 "$W/$p.png"
		fb_pair "fb-quant-$p-nofs" "$p" "-O dither=none" pngquant-nofs \
			pngquant --nofs --force --output "$W/fb-quant-$p-nofs.anchor.png" 256 "$W/$p.png"
		# the same with 8-bit palette entries (beyond the 6-bit DAC: what pngquant writes)
		fb_pair "fb-quant-$p-fs-dac8" "$p" "-O dac=8" pngquant \
			pngquant --force --output "$W/fb-quant-$p-fs-dac8.anchor.png" 256 "$W/$p.png"
		fb_pair "fb-quant-$p-nofs-dac8" "$p" "-O dither=none,dac=8" pngquant-nofs \
			pngquant --nofs --force --output "$W/fb-quant-$p-nofs-dac8.anchor.png" 256 "$W/$p.png"
		fb_pair "fb-quant-$p-im-fs" "$p" "" im-colors-256 \
			convert "$W/$p.png" -dither FloydSteinberg -colors 256 "PNG8:$W/fb-quant-$p-im-fs.anchor.png"
		fb_pair "fb-quant-$p-im-nofs" "$p" "-O dither=none" im-colors-256-nodither \
			convert "$W/$p.png" +dither -colors 256 "PNG8:$W/fb-quant-$p-im-nofs.anchor.png"
		fb_pair "fb-quant-$p-im-fs-dac8" "$p" "-O dac=8" im-colors-256 \
			convert "$W/$p.png" -dither FloydSteinberg -colors 256 "PNG8:$W/fb-quant-$p-im-fs-dac8.anchor.png"
		fb_pair "fb-quant-$p-im-nofs-dac8" "$p" "-O dither=none,dac=8" im-colors-256-nodither \
			convert "$W/$p.png" +dither -colors 256 "PNG8:$W/fb-quant-$p-im-nofs-dac8.anchor.png"
	done
	# workload a onto the framebuffer modes against locus-raster
	if [ ! -f "$W/a.meta" ]; then
		if [ ! -x "$W/gen_workloads" ] && ! build gen_workloads tests/bench/gen_workloads.c; then
			skip fb-a "gen_workloads does not build yet: $B_ERR"; return
		fi
		"$W/gen_workloads" a text -o "$W/a.meta" 2> "$W/gen.log" || { fail fb-a "gen_workloads a"; return; }
	fi
	for v in 13h:vga xga:xga; do
		n=fb-a-${v%%:*} prog=locus-${v#*:}
		: > "$W/r.fbl"
		: > "$W/r.fba"
		ERR="" i=0
		while [ "$i" -lt "$BENCH_RUNS" ] && [ -z "$ERR" ]; do
			once fba /dev/null "$BIN/locus-raster" "$W/a.meta" -o "$W/fb-a.raster.png"
			once fbl /dev/null "$BIN/$prog" "$W/a.meta" -o "$W/$n.png"
			i=$((i + 1))
		done
		if [ -n "$ERR" ]; then fail "$n" "$ERR"; continue; fi
		med "$W/r.fba"
		a_s=$M_S a_mib=$M_MIB a_cpu=$M_CPU
		med "$W/r.fbl"
		r=$(ratio "$a_s" "$M_S")
		line "$n" "$M_S" locus-raster "$a_s" "$M_MIB" "$a_mib" "target=0.77 pass=$(pass "$r" 0.77)" \
			"$(cpu "$M_CPU" "$a_cpu")"
	done
}
