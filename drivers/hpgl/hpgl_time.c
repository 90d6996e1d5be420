/* hpgl_time.c: the plot-time model: trapezoidal moves, corner stops, pen lifts and changes. */
#include <math.h>
#include "hpgl/hpgl.h"

double hpgl_move_time(double len_mm, double v_cms, double a_ms2)
{
	if (len_mm <= 0)
		return 0;
	double v = v_cms * 10, a = a_ms2 * 1000;     /* mm/s, mm/s^2 */
	double ramp = v * v / a;                      /* distance to reach v and stop again */
	if (len_mm >= ramp)
		return len_mm / v + v / a;
	return 2 * sqrt(len_mm / a);
}

void hpgl_time_add(hpgl_time_t *t, const hpgl_profile_t *prof, double travel_pu,
		const popt_pt_t *pts, size_t n)
{
	double up = travel_pu / HPGL_PU_PER_MM;
	t->up_mm += up;
	t->up_s += hpgl_move_time(up, prof->v_up, prof->accel);
	t->lift_s += 2 * prof->t_lift;
	t->lifts++;
	/* pen down: runs between corners sharper than 30 degrees are moved in one go */
	double run = 0;
	const double cos30 = cos(M_PI / 6);
	double dx = 0, dy = 0, l1 = 0;
	if (n > 1) {
		dx = (double)pts[1].x - pts[0].x;
		dy = (double)pts[1].y - pts[0].y;
		l1 = sqrt(dx * dx + dy * dy);
	}
	for (size_t i = 1; i < n; i++) {
		double L = l1 / HPGL_PU_PER_MM;
		run += L;
		t->down_mm += L;
		int stop = i + 1 == n;
		double ex = 0, ey = 0, l2 = 0;
		if (!stop) {
			ex = (double)pts[i + 1].x - pts[i].x;
			ey = (double)pts[i + 1].y - pts[i].y;
			l2 = sqrt(ex * ex + ey * ey);
			stop = l1 > 0 && l2 > 0 && dx * ex + dy * ey < cos30 * l1 * l2;
		}
		if (stop) {
			t->down_s += hpgl_move_time(run, prof->v_down, prof->accel);
			run = 0;
		}
		dx = ex;
		dy = ey;
		l1 = l2;
	}
}
