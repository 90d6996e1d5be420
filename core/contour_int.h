/* contour_int.h: internals shared by the contour*.c files (not part of the public API). */
#ifndef LOCUS_CONTOUR_INT_H
#define LOCUS_CONTOUR_INT_H

#include "msq.h"

/* Record a printf-style error message for contour_error() and return code. */
#define contour_fail msq_fail

#endif
