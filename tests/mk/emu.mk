# emu.mk: the device emulators of the transport tests (tests/emu/): the pen plotter behind a
# pseudo-terminal or a TCP port, which reads what arrives with the HP-GL reader of libdrivers.
TESTPROGS += $(B)/tests/emu-plotter
$(B)/tests/emu-plotter: $(B)/tests/emu/plotemu.o $(B)/libdrivers.a $(B)/libmeta.a
	@mkdir -p $(dir $@)
	$(CC) $(ALL_LDFLAGS) -o $@ $^ $(LDLIBS_ALL)
