/* main-vga.c: locus-vga, a meta file onto VGA mode 13h or 12h (files or a Linux framebuffer). */
#include "cli/fbcli.h"

int main(int argc, char **argv)
{
	return fbcli_main(argc, argv, "locus-vga", &dev_vga_ops, &vga_mode_list);
}
