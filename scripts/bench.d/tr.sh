# tr.sh (sourced by scripts/bench.sh): the device transports (docs/transports.md). Serial
# throughput into the plotter emulator (tests/emu/plotemu.c, a pen that is not the bottleneck)
# at 9600 and 115200 baud against the line's byte rate (baud / 10 for 8N1: anchor "line-rate",
# target ratio 0.95), and the time to deliver workload c's HP-GL through each transport against
# writing it to a file. Needs the emulators that `make check` builds.
bench_tr() {
	tr_e=build/native/tests/emu-plotter tr_u=build/native/tests/emu-usb
	if [ ! -x "$tr_e" ] || ! have_bin locus-hpgl; then
		skip serial-9600 "emu-plotter or locus-hpgl not built (make check builds the emulators)"
		return
	fi
	sh tests/emu/bigjob.sh 300 > "$W/tr-9600.meta"      # about 6 KB: 6 s at 9600 baud
	sh tests/emu/bigjob.sh 2000 > "$W/tr-115200.meta"   # about 40 KB: 3.5 s at 115200
	for baud in 9600 115200; do
		m=$W/tr-$baud.meta
		"$BIN/locus-hpgl" --no-optimize "$m" -o "$W/tr.hpgl" 2> /dev/null
		if ! "$tr_e" --pen-scale 100000 --pen-change 0 --expect "$W/tr.hpgl" -- "$BIN/locus-hpgl" --no-optimize "$m" \
			-o "serial:@TTY@?baud=$baud&flow=xonxoff" > "$W/tr.out" 2> "$W/tr.err"; then
			fail "serial-$baud" "emu-plotter: $(cat "$W/tr.out" "$W/tr.err" | tail -1)"
			continue
		fi
		tr_n=$(tr ' ' '\n' < "$W/tr.out" | sed -n 's/^received=//p')
		tr_s=$(tr ' ' '\n' < "$W/tr.out" | sed -n 's/^seconds=//p')
		tr_line=$(awk -v n="$tr_n" -v b="$baud" 'BEGIN {printf "%.4f", (n - 1) * 10 / b}')
		tr_r=$(ratio "$tr_line" "$tr_s")
		line "serial-$baud" "$tr_s" line-rate "$tr_line" 0 0 "target=0.95 pass=$(pass "$tr_r" 0.95)" \
			"bytes=$tr_n bytes_per_s=$(awk -v n="$tr_n" -v s="$tr_s" 'BEGIN {printf "%.0f", (n - 1) / s}') line_bytes_per_s=$((baud / 10))"
	done
	if ! build gen_workloads tests/bench/gen_workloads.c || ! "$W/gen_workloads" c text -o "$W/c.meta" 2> "$W/gen.log"; then
		skip c-transports "gen_workloads: ${B_ERR:-$(tail -1 "$W/gen.log")}"
		return
	fi
	"$BIN/locus-hpgl" "$W/c.meta" -o "$W/c.hpgl" 2> /dev/null
	if ! measure 3 /dev/null "$BIN/locus-hpgl" "$W/c.meta" -o "$W/c-file.hpgl"; then
		fail c-file "$M_ERR"
		return
	fi
	tr_fs=$M_S tr_fm=$M_MIB
	tr_bytes=$(wc -c < "$W/c.hpgl")
	# serial is line-bound (the rate lines above): workload c would take bytes / 11520 s there
	skip c-serial-115200 "line-bound: $tr_bytes bytes at 11520 B/s take $(awk -v n="$tr_bytes" 'BEGIN {printf "%.1f", n / 11520}') s; serial-115200 measures the rate"
	for tr_t in tcp usb hid; do
		case $tr_t in
		tcp) set -- "$tr_e" --tcp --rcvbuf 0 --rate 1000000000 --pen-scale 100000 --expect "$W/c.hpgl" -- "$BIN/locus-hpgl" "$W/c.meta" -o "tcp:127.0.0.1:@PORT@" ;;
		usb) set -- "$tr_u" --expect "$W/c.hpgl" -- "$BIN/locus-hpgl" "$W/c.meta" -o usb:03f0:0107 ;;
		hid) set -- "$tr_u" --cp2110 --expect "$W/c.hpgl" -- "$BIN/locus-hpgl" "$W/c.meta" -o hid:10c4:ea80 ;;
		esac
		if [ "$tr_t" != tcp ] && { [ ! -x "$tr_u" ] || ! have umockdev-wrapper; }; then
			skip "c-$tr_t" "emu-usb or umockdev not there"
			continue
		fi
		if ! measure 1 "$W/tr.out" "$@"; then
			fail "c-$tr_t" "$M_ERR"
			continue
		fi
		grep -q "bytes=same" "$W/tr.out" || { fail "c-$tr_t" "delivered bytes differ: $(cat "$W/tr.out")"; continue; }
		line "c-$tr_t" "$M_S" "locus-hpgl-to-file" "$tr_fs" "$M_MIB" "$tr_fm" "bytes=$tr_bytes" \
			"note=the-emulator's-start-up-and-device-model-included"
	done
}
