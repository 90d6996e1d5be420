# drivers/module.mk: device framework, scan conversion, transports, and one program per driver.
DRV_MAINS := $(wildcard drivers/main-*.c)
DRV_SRCS := $(filter-out $(DRV_MAINS),$(wildcard drivers/*.c))
$(B)/libdrivers.a: $(DRV_SRCS:%.c=$(B)/%.o)
# drivers/main-NAME.c becomes bin/locus-NAME
PROGRAMS += $(DRV_MAINS:drivers/main-%.c=$(BINDIR)/locus-%)
$(BINDIR)/locus-%: $(B)/drivers/main-%.o $(B)/libdrivers.a $(B)/libmeta.a
	@mkdir -p $(dir $@)
	$(CC) $(ALL_LDFLAGS) -o $@ $^ $(LDLIBS_ALL)
# A driver that needs another library adds "PKGS += NAME" (a pkg-config name) below.
PKGS += libusb-1.0
PKGS += hidapi-libusb
include drivers/printer/printer.mk
