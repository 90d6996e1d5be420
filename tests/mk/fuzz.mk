# tests/mk/fuzz.mk: the libFuzzer harnesses of tests/fuzz/ (clang, `make fuzz`) and the replay of
# their seeds and regression inputs through the normal build (test_fuzz_regress in make check).
FUZZ_HARNESSES := meta_text meta_binary raster scene image hpgl plotmeta imgread vector vecdash resume journal
FUZZ_HARNESSES += svg
fuzz_src_svg := tests/fuzz/fuzz_svg.c
FUZZ_CC     ?= clang
FUZZ_B      := build/fuzz
FUZZ_SAN    := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
# FUZZ_DEFS=-DFUZZ_GUARDS=0 FUZZ_B=build/fuzz-noguard: the harnesses without the pending-fix guards
FUZZ_DEFS   ?=
FUZZ_CFLAGS  = $(STDFLAGS) $(WARNFLAGS) -O1 -g $(MATHFLAGS) $(FUZZ_SAN) -fsanitize=fuzzer-no-link $(FUZZ_DEFS) \
	-Imeta -Idrivers -Icore -Itests/fuzz $(PKG_CFLAGS)
FUZZ_LIBSRC := $(META_SRCS) $(DRV_SRCS) $(CORE_SRCS)
FUZZ_PROGS  := $(FUZZ_HARNESSES:%=$(FUZZ_B)/fuzz_%)
# what each harness is built from (the binary meta harness is the text one with the magic added)
fuzz_src_meta_text := tests/fuzz/fuzz_meta.c
fuzz_src_meta_binary := tests/fuzz/fuzz_meta.c
fuzz_def_meta_binary := -DFUZZ_META_BINARY
fuzz_src_raster := tests/fuzz/fuzz_raster.c
fuzz_src_scene := tests/fuzz/fuzz_scene.c
fuzz_src_image := tests/fuzz/fuzz_image.c
fuzz_src_hpgl := tests/fuzz/fuzz_hpgl.c
fuzz_src_plotmeta := tests/fuzz/fuzz_plotmeta.c
fuzz_src_imgread := tests/fuzz/fuzz_imgread.c
fuzz_src_vector := tests/fuzz/fuzz_vector.c
fuzz_src_vecdash := tests/fuzz/fuzz_vecdash.c
fuzz_src_resume := tests/fuzz/fuzz_resume.c
fuzz_src_journal := tests/fuzz/fuzz_journal.c

.PHONY: fuzz-programs
fuzz-programs: $(FUZZ_PROGS)

$(FUZZ_B)/lib/%.o: %.c
	@mkdir -p $(dir $@)
	$(FUZZ_CC) $(FUZZ_CFLAGS) -MMD -MP -c $< -o $@
$(FUZZ_B)/liblocus.a: $(FUZZ_LIBSRC:%.c=$(FUZZ_B)/lib/%.o)
	@mkdir -p $(dir $@)
	rm -f $@ && ar rcs $@ $^
# (-MMD: the Makefile's include of build/**/*.d rebuilds a harness when a header it reads changes)
$(FUZZ_HARNESSES:%=$(FUZZ_B)/h_%.o): $(FUZZ_B)/h_%.o: tests/fuzz/fuzz.h $(wildcard tests/fuzz/fuzz_*.c)
	@mkdir -p $(dir $@)
	$(FUZZ_CC) $(FUZZ_CFLAGS) $(fuzz_def_$*) -MMD -MP -c $(fuzz_src_$*) -o $@
$(FUZZ_PROGS): $(FUZZ_B)/fuzz_%: $(FUZZ_B)/h_%.o $(FUZZ_B)/liblocus.a
	$(FUZZ_CC) $(FUZZ_SAN) -fsanitize=fuzzer -o $@ $^ $(LDLIBS_ALL)

# The same harnesses in the normal build (gcc, or under SANITIZE=1 its sanitizers), each entry
# renamed, linked into one program that replays fixtures/fuzz/HARNESS/ and fixtures/fuzz/regress/.
TESTPROGS += $(B)/tests/test_fuzz_regress
$(FUZZ_HARNESSES:%=$(B)/tests/fuzz/%.o): $(B)/tests/fuzz/%.o: tests/fuzz/fuzz.h $(wildcard tests/fuzz/fuzz_*.c) | deps-ok
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -Itests/fuzz $(fuzz_def_$*) -DFUZZ_ENTRY=fuzz_entry_$* -c $(fuzz_src_$*) -o $@
$(B)/tests/test_fuzz_regress: $(B)/tests/fuzz/regress.o $(FUZZ_HARNESSES:%=$(B)/tests/fuzz/%.o) \
		$(B)/libcore.a $(B)/libdrivers.a $(B)/libmeta.a
	@mkdir -p $(dir $@)
	$(CC) $(ALL_LDFLAGS) -o $@ $^ $(LDLIBS_ALL)
$(B)/tests/fuzz/regress.o: tests/fuzz/regress.c | deps-ok
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -c $< -o $@
