# core/module.mk: the renderer library and locus-render (which writes through the drivers' transport).
CORE_SRCS := $(filter-out core/locus-render.c,$(wildcard core/*.c))
$(B)/libcore.a: $(CORE_SRCS:%.c=$(B)/%.o)
ifneq ($(wildcard core/locus-render.c),)
PROGRAMS += $(BINDIR)/locus-render
endif
$(BINDIR)/locus-render: $(B)/core/locus-render.o $(B)/libcore.a $(B)/libdrivers.a $(B)/libmeta.a
	@mkdir -p $(dir $@)
	$(CC) $(ALL_LDFLAGS) -o $@ $^ $(LDLIBS_ALL)
