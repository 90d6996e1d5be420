/* emu.h: what the device emulators of the transport tests share (tests/emu/). */
#ifndef LOCUS_EMU_H
#define LOCUS_EMU_H

#include <stddef.h>

/* Compare the ng bytes got with the HP-GL file expect: prints " bytes=same|differ@N(...)" and
 * " strokes=same|differ expected=N got=N missing=N extra=N" (or why it could not read them) on
 * stdout. Returns 0 when bytes and strokes are the same, else 1. */
int emu_compare(const unsigned char *got, size_t ng, const char *expect);

#endif
