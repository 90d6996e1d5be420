# meta/module.mk: the meta-language library and the locus-meta tool.
META_SRCS := $(filter-out meta/locus-meta.c,$(wildcard meta/*.c))
$(B)/libmeta.a: $(META_SRCS:%.c=$(B)/%.o)
PROGRAMS += $(BINDIR)/locus-meta
$(BINDIR)/locus-meta: $(B)/meta/locus-meta.o $(B)/libdrivers.a $(B)/libmeta.a
	@mkdir -p $(dir $@)
	$(CC) $(ALL_LDFLAGS) -o $@ $^ $(LDLIBS_ALL)
