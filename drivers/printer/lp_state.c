/* lp_state.c: what every part of locus-printer shares: the spool directory and the replay lock.
 * It calls nothing of the other lp_*.c files, so that they all can call it (calls go one way:
 * lp_main -> lp_caps -> lp_raster -> lp_job -> lp_drivers, lp_link, lp_state). */
#include <pthread.h>
#include <stdio.h>
#include "printer/lp.h"

static char spool_dir[1024];
static pthread_mutex_t replay_lock = PTHREAD_MUTEX_INITIALIZER;

void lp_set_spool_dir(const char *dir)
{
	snprintf(spool_dir, sizeof spool_dir, "%s", dir ? dir : "");
}

const char *lp_spool_dir(void)
{
	return spool_dir[0] ? spool_dir : papplGetTempDir();
}

void lp_lock(void)
{
	pthread_mutex_lock(&replay_lock);
}

void lp_unlock(void)
{
	pthread_mutex_unlock(&replay_lock);
}
