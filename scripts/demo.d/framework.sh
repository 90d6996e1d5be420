# scripts/demo.d/framework.sh (sourced by scripts/demo.sh): the framework's anti-aliased mode
# beside the exact reference, on the line-state fixture (the default scene is one ray-traced
# image, pixel-aligned, which anti-aliasing leaves exactly as it is).
"$BIN/locus-play" -d png -o out/strokes.png fixtures/meta/strokes.meta
"$BIN/locus-play" -d png -O antialias=4 -o out/strokes-antialias.png fixtures/meta/strokes.meta
echo "demo: fixtures/meta/strokes.meta -> out/strokes.png (exact), out/strokes-antialias.png (4x4 samples a pixel)"
