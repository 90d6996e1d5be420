# drivers/module.mk: device framework, scan conversion, transports, and one program per driver.
# Sources are found by wildcard in the subsystem folders (docs/drivers.md, "Where things are"):
# a new file needs no edit here. drivers/cli/main-NAME.c becomes bin/locus-NAME.
DRV_MAINS := $(wildcard drivers/cli/main-*.c)
DRV_SRCS := $(filter-out $(DRV_MAINS) drivers/printer/%,$(wildcard drivers/*/*.c drivers/*/*/*.c))
$(B)/libdrivers.a: $(DRV_SRCS:%.c=$(B)/%.o)
PROGRAMS += $(DRV_MAINS:drivers/cli/main-%.c=$(BINDIR)/locus-%)
$(BINDIR)/locus-%: $(B)/drivers/cli/main-%.o $(B)/libdrivers.a $(B)/libmeta.a
	@mkdir -p $(dir $@)
	$(CC) $(ALL_LDFLAGS) -o $@ $^ $(LDLIBS_ALL)
# A driver that needs another library adds "PKGS += NAME" (a pkg-config name) below.
PKGS += libusb-1.0
PKGS += hidapi-libusb
PKGS += libxml-2.0
include drivers/printer/printer.mk
