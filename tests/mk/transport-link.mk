# transport-link.mk: locus-meta and locus-render write their output through drivers/transport.c
# (safe temporaries, devices in place, signals), so they link libdrivers.a after libmeta.a.
# This belongs in meta/module.mk and core/module.mk; it lives here (the one included hook) until
# the owners of those files move it.
$(BINDIR)/locus-meta: $(B)/libdrivers.a
$(BINDIR)/locus-render: $(B)/libdrivers.a
