#!/bin/sh
# t_layers.sh: the folder rule of drivers/ (docs/drivers.md, "Layers"), read from the #include
# lines by tests/tools/layers.py: util below everything; io, geom, quant and hpgl/read on util
# only; image on io; render on geom; device on render, geom and io; the families on device and
# below and never on each other; diff and import on the families' public headers; cli on
# anything; an _int.h never read outside its folder; libcore and libmeta read nothing of drivers/.
# It also finds the circles: objects (of $TESTBIN's build) that need each other's symbols.
# What still breaks the rule is listed below with the reason, so that a new break fails; an
# entry that no longer breaks it fails too, until it is taken off the list.
# `python3 tests/tools/layers.py count` prints the counts of circles and upward includes.
. tests/lib.sh
command -v python3 >/dev/null 2>&1 || { ok "layer rule # SKIP python3 not found"; done_tests; }
cat > "$T/allow" <<'LIST'
# FILE -> HEADER it includes against the rule      # why it is still there, and what removes it
# circle: the files whose objects need each other  # why, and what breaks it
LIST
python3 tests/tools/layers.py check "$T/allow" "$(dirname "$TESTBIN")" || FAILED=1
done_tests
