# tests/mk/fault.mk: the fault-injection library of tests/t_fault.sh (native build only: under
# SANITIZE=1 the sanitizer owns malloc and the script skips).
ifneq ($(SANITIZE),1)
TESTPROGS += $(B)/tests/libfault.so
$(B)/tests/libfault.so: tests/fault/fault.c
	@mkdir -p $(dir $@)
	$(CC) -std=c11 $(WARNFLAGS) -O1 -g -fPIC -shared -o $@ $< -ldl
endif
