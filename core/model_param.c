/* model_param.c: the pieces of the defining parameters below model_eval.c: seeded value noise and the
 * level of a smooth Mandelbrot process (model_param itself, which may evaluate another shape, is in
 * model_eval.c). */
#include "model.h"

#include <math.h>

int model_de_level(const model_param_t *c, double *m0)
{
	if (c->kind != MODEL_C_MANDEL || !c->smooth || c->amp == 0)
		return 0;
	*m0 = -c->c0 * c->maxit / c->amp;
	return *m0 > 0 && *m0 < c->maxit;
}

static unsigned hash3(unsigned seed, int x, int y, int z)
{
	unsigned h = seed * 0x9e3779b1u ^ (unsigned)x * 0x85ebca77u ^ (unsigned)y * 0xc2b2ae3du ^ (unsigned)z * 0x27d4eb2fu;
	h ^= h >> 15;
	h *= 0x2c1b3c6du;
	h ^= h >> 12;
	h *= 0x297a2d39u;
	h ^= h >> 15;
	return h;
}

double model_noise(unsigned seed, double x, double y, double z)
{
	double fx = floor(x), fy = floor(y), fz = floor(z);
	int ix = (int)fx, iy = (int)fy, iz = (int)fz;
	double tx = x - fx, ty = y - fy, tz = z - fz;
	double sx = tx * tx * (3 - 2 * tx), sy = ty * ty * (3 - 2 * ty), sz = tz * tz * (3 - 2 * tz);
	double v[8];
	for (int k = 0; k < 8; k++)
		v[k] = hash3(seed, ix + (k & 1), iy + ((k >> 1) & 1), iz + (k >> 2)) / 2147483647.5 - 1.0;
	double x00 = v[0] + sx * (v[1] - v[0]), x10 = v[2] + sx * (v[3] - v[2]);
	double x01 = v[4] + sx * (v[5] - v[4]), x11 = v[6] + sx * (v[7] - v[6]);
	double y0 = x00 + sy * (x10 - x00), y1 = x01 + sy * (x11 - x01);
	return y0 + sz * (y1 - y0);
}
