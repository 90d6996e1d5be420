#!/bin/sh
# demo.sh: placeholder until the drivers land.
echo "demo: nothing to run yet" >&2
