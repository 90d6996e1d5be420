# scripts/demo.d/fb.sh (sourced by scripts/demo.sh): the default scene on the framebuffer devices:
# VGA mode 13h as a PCX (the period's screenshot format) and XGA 1024x768x256 as an indexed PNG.
"$BIN/locus-vga" out/default.meta -o out/default.vga-13h.pcx &&
	echo "demo: vga 13h -> out/default.vga-13h.pcx (320x200, 256 colours, 5:6 pixels)"
"$BIN/locus-xga" out/default.meta -o out/default.xga.png &&
	echo "demo: xga 1024x768x256 -> out/default.xga.png (indexed PNG)"
