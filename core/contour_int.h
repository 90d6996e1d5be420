/* contour_int.h: internals shared by the contour*.c files (not part of the public API). */
#ifndef LOCUS_CONTOUR_INT_H
#define LOCUS_CONTOUR_INT_H

/* Record a printf-style error message for contour_error() and return code. */
int contour_fail(int code, const char *fmt, ...)
#ifdef __GNUC__
	__attribute__((format(printf, 2, 3)))
#endif
	;

#endif
