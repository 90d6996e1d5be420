/* wire.h: wireframes: a 3D shape drawn as projected cross-section contours (plotter-friendly vectors).
 *
 * The shape's clip box is cut by `slices` equally spaced planes
 * perpendicular to an axis (at the centres of equal slabs). On each plane f
 * is sampled on a res x res grid covering the box, the zero iso-line is
 * extracted by contour_extract (marching squares, joined polylines) and each
 * polyline is mapped back to 3D and projected through the camera. Every
 * polyline becomes one stroked path, so a pen plotter draws it in one
 * pen-down stroke. Hidden lines are not removed (a draft sketch).
 */
#ifndef LOCUS_WIRE_H
#define LOCUS_WIRE_H

#include <stddef.h>
#include <stdint.h>
#include "camera.h"
#include "locus_meta.h"
#include "model.h"

/* Draw the sections of s (axis 0 = x, 1 = y, 2 = z) in colour with line
 * width, shifted by xoff pixels. Adds the number of drawn segments to
 * *segments. Returns 0 or -1 with a message. */
int wire_draw(meta_writer_t *w, const cam_t *cam, const model_shape_t *s, int axis, int slices,
              int res, double width, meta_rgb_t colour, double xoff, uint64_t *segments,
              char *err, size_t errlen);

#endif
