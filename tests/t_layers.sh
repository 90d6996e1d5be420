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
drivers/ps/psdev.c -> cli/run.h   # dev_err_is_oom (out of memory told from message text) is in cli/run.c, the job runner issue 20 is changing; phase 2 makes errors travel as codes and drops it
# circle: the files whose objects need each other  # why, and what breaks it
circle: drivers/device/device.c drivers/device/fit.c drivers/device/options.c drivers/device/vecsupply.c   # fit.c, options.c and vecsupply.c report through dev_fail, in device.c (issue 20's); phase 2 moves dev_new/dev_free/dev_fail/dev_error to device/instance.c
circle: drivers/hpgl/dev_hpgl.c drivers/hpgl/hpgl_page.c   # hpgl_page.c calls hpgl_dev_grow and hpgl_dev_nomem, in dev_hpgl.c (issue 20's); phase 2 moves them to hpgl/hpgl_dev.c
circle: drivers/io/escb.c drivers/io/file.c drivers/io/hid.c drivers/io/link_journal.c drivers/io/serial.c drivers/io/signals.c drivers/io/tcp.c drivers/io/transport.c drivers/io/usb.c   # the links call io_oom, io_link_fail, io_link_tempfail, io_set_err, tr_now_ms, tr_parse_long, tr_query_next in transport.c, which calls them (issue 20's files); phase 2 splits io/link_util.c and the link table
circle: core/model_eval.c core/model_param.c   # core/ (not this phase): model_param and model_eval recurse into each other; fold model_param.c into model_eval.c
circle: core/scene.c core/scene_shape.c   # core/ (not this phase): scene_parse_colour and scene_warn, in scene.c, go to scene_lex.c
circle: core/scene_2d.c core/scene_render.c   # core/ (not this phase): scene_add_warning, in scene_render.c, goes to scene_lex.c
circle: meta/read_binary.c meta/read_text.c meta/reader.c   # meta/ (not this phase): meta_rd_fail, meta_rd_fill, meta_rd_runs go to a file of their own, as image/imgread_io.c
LIST
python3 tests/tools/layers.py check "$T/allow" "$(dirname "$TESTBIN")" || FAILED=1
done_tests
