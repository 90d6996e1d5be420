#!/bin/sh
# bench.sh: placeholder until the benchmarks land.
echo "bench: nothing yet" >&2
