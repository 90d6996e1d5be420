/* hpgl_link.h: HP-GL as the language of device links (io/lang.h): the job journal's checkpoints
 * and restore through the HP-GL tracker (hpgl/read/hpgl_track.h), and, on links that read the
 * plotter's replies (flow=escb), HP-GL's handshakes: ESC.L (buffer size) and OI (identification)
 * at the open, ESC.B (free buffer space) before and after each chunk, OE (error) at the end.
 */
#ifndef LOCUS_HPGL_LINK_H
#define LOCUS_HPGL_LINK_H

#include "io/lang.h"

extern const io_lang_t hpgl_link_lang;

/* Make HP-GL the language of this program's device links (io_set_lang): before the first open. */
void hpgl_link_register(void);

#endif
