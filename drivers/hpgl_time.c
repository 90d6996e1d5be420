/* hpgl_time.c: the plot-time model: trapezoidal moves, corner stops, pen lifts and changes. */
#include <math.h>
#include "hpgl.h"

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
	for (size_t i = 1; i < n; i++) {
		double dx = (double)pts[i].x - pts[i - 1].x, dy = (double)pts[i].y - pts[i - 1].y;
		double L = sqrt(dx * dx + dy * dy) / HPGL_PU_PER_MM;
		run += L;
		t->down_mm += L;
		int stop = i + 1 == n;
		if (!stop) {
			double ex = (double)pts[i + 1].x - pts[i].x, ey = (double)pts[i + 1].y - pts[i].y;
			double l1 = sqrt(dx * dx + dy * dy), l2 = sqrt(ex * ex + ey * ey);
			stop = l1 > 0 && l2 > 0 && (dx * ex + dy * ey) / (l1 * l2) < cos30;
		}
		if (stop) {
			t->down_s += hpgl_move_time(run, prof->v_down, prof->accel);
			run = 0;
		}
	}
}
