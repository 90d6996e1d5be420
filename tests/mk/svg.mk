# tests/mk/svg.mk: the SVG device's checker renders SVG with librsvg (dlopen) on cairo.
TESTPROGS += $(B)/tests/svg_render
$(B)/tests/svg_render: tests/svg/svg_render.c
	@mkdir -p $(dir $@)
	$(CC) $(STDFLAGS) $(WARNFLAGS) $(OPT) $(CFLAGS) $(SANFLAGS) $$(pkg-config --cflags cairo) -o $@ $< \
		$(ALL_LDFLAGS) $$(pkg-config --libs cairo) -ldl
