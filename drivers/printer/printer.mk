# drivers/printer/printer.mk: bin/locus-printer, the PAPPL printer application (docs/printer.md).
# Its objects are its own: they stay out of libdrivers.a, which they link against.
LP_SRCS := $(wildcard drivers/printer/*.c)
# Asked of pkg-config on first use (after deps-ok installed libpappl-dev), then kept.
LP_CFLAGS = $(eval LP_CFLAGS := $$(shell pkg-config --cflags pappl 2>/dev/null))$(LP_CFLAGS)
LP_LIBS = $(eval LP_LIBS := $$(shell pkg-config --libs pappl 2>/dev/null))$(LP_LIBS)
$(B)/drivers/printer/%.o: drivers/printer/%.c | deps-ok
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(LP_CFLAGS) -c $< -o $@
PROGRAMS += $(BINDIR)/locus-printer
$(BINDIR)/locus-printer: $(LP_SRCS:%.c=$(B)/%.o) $(B)/libdrivers.a $(B)/libmeta.a
	@mkdir -p $(dir $@)
	$(CC) $(ALL_LDFLAGS) -o $@ $^ $(LP_LIBS) $(LDLIBS_ALL)
