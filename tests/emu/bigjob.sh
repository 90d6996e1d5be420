#!/bin/sh
# bigjob.sh N: a meta file of N short pen strokes on a 200 mm page, deterministic (for jobs
# larger than the buffers between a sender and the line: the transport tests and benchmark).
awk -v n="${1:-6000}" 'BEGIN {
	print "LOCUS-META 1"; print "page 200 200"; print "colour #000000"; print "width 0.3"
	s = 12345
	for (i = 0; i < n; i++) {
		s = (s * 1103515245 + 12345) % 2147483648; x = 5 + (s % 19000) / 100
		s = (s * 1103515245 + 12345) % 2147483648; y = 5 + (s % 19000) / 100
		printf "stroke\nmove %.2f %.2f\ndraw %.2f %.2f\nend\n", x, y, x + 3, y + 2
	}
	print "end-page"
}'
