# tests/module.mk: every tests/unit/test_*.c is one unit-test program in $(B)/tests/.
UNIT_SRCS := $(wildcard tests/unit/test_*.c)
TESTPROGS += $(UNIT_SRCS:tests/unit/%.c=$(B)/tests/%)
$(B)/tests/test_%: $(B)/tests/unit/test_%.o $(B)/libcore.a $(B)/libdrivers.a $(B)/libmeta.a
	@mkdir -p $(dir $@)
	$(CC) $(ALL_LDFLAGS) -o $@ $^ $(LDLIBS_ALL)
# Test programs that need rules of their own (fuzzers, device harnesses) come in tests/mk/*.mk.
include $(wildcard tests/mk/*.mk)
