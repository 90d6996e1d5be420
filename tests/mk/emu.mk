# emu.mk: the device emulators of the transport tests (tests/emu/): the pen plotter behind a
# pseudo-terminal or a TCP port, which reads what arrives with the HP-GL reader of libdrivers.
TESTPROGS += $(B)/tests/emu-plotter
$(B)/tests/emu-plotter: $(B)/tests/emu/plotemu.o $(B)/tests/emu/emu_compare.o $(B)/libdrivers.a $(B)/libmeta.a
	@mkdir -p $(dir $@)
	$(CC) $(ALL_LDFLAGS) -o $@ $^ $(LDLIBS_ALL)
# The USB printer emulator: a libumockdev testbed with a usbdevfs ioctl handler (glib).
TESTPROGS += $(B)/tests/emu-usb
$(B)/tests/emu/usbemu.o: CFLAGS += $(shell pkg-config --cflags umockdev-1.0 2>/dev/null)
$(B)/tests/emu-usb: $(B)/tests/emu/usbemu.o
	@mkdir -p $(dir $@)
	$(CC) $(ALL_LDFLAGS) -o $@ $^ $(shell pkg-config --libs umockdev-1.0 2>/dev/null)
# Pen-down segments of HP-GL files (through the HP-GL reader), for the resume tests.
TESTPROGS += $(B)/tests/hpgl-segments
$(B)/tests/hpgl-segments: $(B)/tests/emu/hpglseg.o $(B)/libdrivers.a $(B)/libmeta.a
	@mkdir -p $(dir $@)
	$(CC) $(ALL_LDFLAGS) -o $@ $^ $(LDLIBS_ALL)
