# tests/mk/fbdev.mk: the fake framebuffer harness (libumockdev) for tests/t_fbdev.sh.
# Not sanitized itself: it only serves ioctls; the program under test runs in its own build.
FBH_CFLAGS = $(STDFLAGS) $(WARNFLAGS) -O1 -g $(shell pkg-config --cflags umockdev-1.0 2>/dev/null)
FBH_LIBS = $(shell pkg-config --libs umockdev-1.0 2>/dev/null)
TESTPROGS += $(B)/tests/fbharness
$(B)/tests/fbharness: tests/fbdev/fbharness.c
	@mkdir -p $(dir $@)
	$(CC) $(FBH_CFLAGS) -o $@ $< $(FBH_LIBS)
