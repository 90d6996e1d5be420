/* test_meta_flat.c: the reader's count of flattened path points (spec §6) is exactly the number
 * of points the reference flattening (drivers/geom/flatten.c) stores, on random paths of moves,
 * draws, arcs, circles and closes (close after close included), and its chord counts are §5.4's. */
#include <stdlib.h>
#include "meta_int.h"
#include "geom/scan.h"
#include "unit.h"

static unsigned seed = 12345;
static unsigned rnd(unsigned n)
{
	seed = seed * 1103515245u + 12345u;
	return (seed >> 8) % n;
}

int main(void)
{
	int bad_paths = 0, paths = 0;
	for (int trial = 0; trial < 200; trial++) {
		char *text = NULL;
		size_t len = 0;
		FILE *f = open_memstream(&text, &len);
		fprintf(f, "LOCUS-META 1\npage 64 64\nstroke\n");
		int has = 0;
		for (int k = 0; k < 40; k++) {
			unsigned c = rnd(5);
			int r = rnd(3) == 0 ? 1 + (int)rnd(400) : (int)rnd(2000000) + 1;
			if (c == 0 || !has) {
				fprintf(f, "move %u %u\n", rnd(64), rnd(64));
				has = 1;
			} else if (c == 1) {
				fprintf(f, "draw %u %u\n", rnd(64), rnd(64));
			} else if (c == 2) {
				fprintf(f, "arc 30 30 %d.%03d %d %d\n", r / 1000, r % 1000, (int)rnd(720) - 360,
					(int)rnd(721) - 360);
			} else if (c == 3) {
				fprintf(f, "circle 30 30 %d.%03d\n", r / 1000, r % 1000);
				has = 0;
			} else {
				fprintf(f, "close\n");
			}
		}
		fprintf(f, "end\nend-page\n");
		fclose(f);
		meta_reader_t *rd = meta_reader_mem(text, len, "random");
		scan_path_t p;
		memset(&p, 0, sizeof p);
		meta_cmd_t cmd;
		int rc, same = 1;
		while ((rc = meta_read(rd, &cmd)) == 1) {
			switch (cmd.op) {
			case META_MOVE: scan_path_move(&p, cmd.f[0], cmd.f[1]); break;
			case META_DRAW: scan_path_draw(&p, cmd.f[0], cmd.f[1]); break;
			case META_ARC: scan_path_arc(&p, cmd.f[0], cmd.f[1], cmd.f[2], cmd.f[3], cmd.f[4]); break;
			case META_CIRCLE: scan_path_circle(&p, cmd.f[0], cmd.f[1], cmd.f[2]); break;
			case META_CLOSE: scan_path_close(&p); break;
			default: continue;
			}
			if (rd->chk.flat != p.npts)
				same = 0;
		}
		paths++;
		if (rc != 0 || !same) {
			bad_paths++;
			if (bad_paths == 1)
				printf("# first disagreement in trial %d (rc %d: %s)\n", trial, rc, meta_reader_error(rd));
		}
		scan_path_free(&p);
		meta_reader_free(rd);
		free(text);
	}
	CHECK(bad_paths == 0, "reader's flattened count = geom/flatten.c's points on %d random paths", paths);
	int agree = 1;
	for (int64_t r = 1; r <= 1000000000; r = r * 3 + 7)
		if (meta_circle_chords(r) != scan_circle_chords(r))
			agree = 0;
	CHECK(agree, "meta_circle_chords agrees with scan_circle_chords from 1 to 10^9 thousandths");
	CHECK(meta_circle_chords(1000000000) == 8886, "radius 10^6 pixels: 8886 chords (the most)");
	CHECK(meta_arc_chords(1000, 90000) == (meta_circle_chords(1000) * 90000 + 359999) / 360000,
		"a quarter arc: ceil(M/4) chords");
	return UNIT_DONE();
}
