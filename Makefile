# Locus top-level Makefile. Each module adds its objects, programs and tests
# in its own module.mk; this file holds the shared rules and the user targets.
#
#   make            build every program into bin/
#   make demo       render the default scene and replay it through every driver into out/
#   make check      unit, golden, round-trip and bad-input tests (SANITIZE=1: under ASan+UBSan)
#   make bench      benchmarks against the anchors; BENCH lines also go to out/bench.txt
#   make install    PREFIX=/usr/local DESTDIR=
#   make fuzz       build the libFuzzer harnesses with clang, run each FUZZ_SECONDS (60) seconds

VERSION    := 0.1.0
PREFIX     ?= /usr/local
DESTDIR    ?=
CC         ?= cc
OPT        ?= -O2 -march=native
CFLAGS     ?= -g
STDFLAGS   := -std=c11 -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE -DLOCUS_VERSION='"$(VERSION)"'
WARNFLAGS  := -Wall -Wextra
MATHFLAGS  := -fno-math-errno
PKGS       := libpng zlib libxml-2.0

ifeq ($(SANITIZE),1)
B          := build/asan
BINDIR     := build/asan/bin
SANFLAGS   := -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all
OPT        := -O1
else
B          := build/native
BINDIR     := bin
SANFLAGS   :=
endif

# Asked of pkg-config on first use (after deps-ok may have installed them), then kept.
PKG_CFLAGS = $(eval PKG_CFLAGS := $$(shell pkg-config --cflags $(PKGS) 2>/dev/null))$(PKG_CFLAGS)
PKG_LIBS   = $(eval PKG_LIBS := $$(shell pkg-config --libs $(PKGS) 2>/dev/null))$(PKG_LIBS)
ALL_CFLAGS  = $(STDFLAGS) $(WARNFLAGS) $(OPT) $(MATHFLAGS) $(CFLAGS) $(SANFLAGS) -Imeta -Idrivers -Icore $(PKG_CFLAGS) -MMD -MP
LDLIBS_ALL  = $(PKG_LIBS) -lpthread -lm
ALL_LDFLAGS = $(SANFLAGS) $(LDFLAGS)

PROGRAMS :=
TESTPROGS :=
LIBS :=

.PHONY: all demo check bench install deps-ok clean programs
# keep intermediate objects: rebuilds stay incremental
.SECONDARY:
all: deps-ok programs

include meta/module.mk
include drivers/module.mk
include core/module.mk
include tests/module.mk

programs: $(PROGRAMS)

# Dependencies: the script installs missing Debian packages when run as root,
# otherwise prints the exact apt-get line and fails.
deps-ok:
	@scripts/deps.sh build

$(B)/%.o: %.c | deps-ok
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -c $< -o $@

$(B)/lib%.a:
	@mkdir -p $(dir $@)
	rm -f $@ && ar rcs $@ $^

demo: all
	@scripts/demo.sh

check: all $(TESTPROGS)
	@scripts/deps.sh check
	@BIN=$(BINDIR) TESTBIN=$(B)/tests SANITIZE=$(SANITIZE) LOCUS_LDLIBS="$(LDLIBS_ALL)" tests/run.sh

# Re-record the expected outputs on purpose and print what changed through locus-diff.
.PHONY: fixtures
fixtures: all $(TESTPROGS)
	@BIN=$(BINDIR) TESTBIN=$(B)/tests scripts/fixtures.sh

bench: all
	@scripts/deps.sh bench
	@BIN=$(BINDIR) scripts/bench.sh

install: all
	install -d $(DESTDIR)$(PREFIX)/bin $(DESTDIR)$(PREFIX)/lib/pkgconfig $(DESTDIR)$(PREFIX)/include/locus $(DESTDIR)$(PREFIX)/share/man/man1
	install -m 755 $(PROGRAMS) $(DESTDIR)$(PREFIX)/bin/
	install -m 644 $(B)/libmeta.a $(DESTDIR)$(PREFIX)/lib/liblocusmeta.a
	install -m 644 meta/locus_meta.h meta/opcodes.def $(DESTDIR)$(PREFIX)/include/locus/
	sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@VERSION@|$(VERSION)|' meta/locus-meta.pc.in > $(DESTDIR)$(PREFIX)/lib/pkgconfig/locus-meta.pc
	install -m 644 docs/man/*.1 $(DESTDIR)$(PREFIX)/share/man/man1/

# The harnesses and their rules are in tests/mk/fuzz.mk, the runner in tests/fuzz/run.sh.
FUZZ_SECONDS ?= 60
.PHONY: fuzz
fuzz: deps-ok
	@scripts/deps.sh fuzz
	@command -v $(FUZZ_CC) >/dev/null 2>&1 || { echo "make fuzz: $(FUZZ_CC) not found (Debian: apt-get install clang libclang-rt-14-dev)" >&2; exit 69; }
	@$(MAKE) --no-print-directory fuzz-programs
	@FUZZ_SECONDS=$(FUZZ_SECONDS) tests/fuzz/run.sh

clean:
	rm -rf build bin out

-include $(shell find build -name '*.d' 2>/dev/null)
