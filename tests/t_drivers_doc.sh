#!/bin/sh
# t_drivers_doc.sh: docs/drivers.md's worked examples are real: the raster and the SVG device
# compile as written, and the SVG one, registered in a tiny program, replays a fixture into SVG
# that librsvg draws like locus-raster (a new vector device needs only docs/drivers.md).
. tests/lib.sh
L=$(dirname "$TESTBIN")
SAN=""
[ "${SANITIZE:-}" = 1 ] && SAN="-fsanitize=address,undefined"
CC=${CC:-cc}
python3 - "$T" <<'PY' || { notok "examples not found in docs/drivers.md"; done_tests; }
import sys
s = open('docs/drivers.md').read(); t = sys.argv[1]
for mark, name in (('/* dev_mine.c:', 'mine'), ('/* dev_svg.c:', 'svg')):
    i = s.index(mark); j = s.index('```', i)
    open('%s/doc-%s.c' % (t, name), 'w').write(s[i:j].replace('dev_svg_ops', 'dev_docsvg_ops'))
PY
cat > "$T/main.c" <<'C'
#include <stdio.h>
#include "device/device.h"
extern const dev_ops_t dev_docsvg_ops;
int main(int argc, char **argv)
{
	char err[256];
	(void)argc;
	meta_reader_t *r = meta_reader_open(argv[1], err, sizeof err);
	io_transport_t *t = r ? io_open_write(argv[2], err, sizeof err) : NULL;
	if (!t)
		return 66;
	dev_device_t *d = dev_new(&dev_docsvg_ops, t);
	int rc = dev_play(r, d);
	io_close(t, rc ? IO_ABORT : IO_COMMIT);
	dev_free(d);
	meta_reader_free(r);
	return rc != 0;
}
C
F="-std=c11 -Wall -Wextra -Werror -D_POSIX_C_SOURCE=200809L -Imeta -Idrivers $SAN"
check "the raster example (dev_mine.c) compiles without a warning" $CC $F -c "$T/doc-mine.c" -o "$T/mine.o"
check "the SVG example compiles without a warning" $CC $F -c "$T/doc-svg.c" -o "$T/svg.o"
if $CC $F "$T/main.c" "$T/svg.o" "$L/libdrivers.a" "$L/libmeta.a" ${LOCUS_LDLIBS:-$(pkg-config --libs libpng zlib) -lpthread -lm} -o "$T/docsvg"; then
	ok "the SVG example links as a program"
	"$T/docsvg" fixtures/meta/f-test.meta "$T/f.svg"
	"$BIN/locus-raster" -o "$T/f.png" fixtures/meta/f-test.meta
	if "$TESTBIN/svg_render" "$T/f.svg" "$T/f-svg.png" 160 120 2>/dev/null; then
		check "its SVG of the F test, drawn by librsvg, is within 25 dB of locus-raster" \
			"$BIN/locus-diff" --psnr 25 "$T/f.png" "$T/f-svg.png"
	else
		ok "librsvg missing # SKIP"
	fi
else
	notok "the SVG example does not link"
fi
done_tests
