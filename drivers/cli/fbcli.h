/* fbcli.h: the program shared by locus-vga and locus-xga (fbcli.c). */
#ifndef LOCUS_FBCLI_H
#define LOCUS_FBCLI_H

#include "fb/fbmode.h"

/* The whole program locus-vga / locus-xga: options, --list-modes, -o fb:NODE, the job, for
 * the device ops with its mode list ml. Prints its own messages; returns the exit status. */
int fbcli_main(int argc, char **argv, const char *prog, const dev_ops_t *ops, const fbm_modes_t *ml);

#endif
