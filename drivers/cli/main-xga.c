/* main-xga.c: locus-xga, a meta file onto XGA 1024x768x256 or 640x480 5-6-5. */
#include "cli/fbcli.h"

int main(int argc, char **argv)
{
	return fbcli_main(argc, argv, "locus-xga", &dev_xga_ops, &xga_mode_list);
}
