/* gslerr.c - GSL's error handler off around the library's GSL calls (gslerr.h). */
#include "core/gslerr.h"

#include <gsl/gsl_errno.h>
#include <pthread.h>

static pthread_mutex_t quiet_lock = PTHREAD_MUTEX_INITIALIZER;
static unsigned long quiet_depth;             /* begins not yet ended */
static gsl_error_handler_t *quiet_saved;      /* the caller's handler */

void sl_gsl_quiet_begin(void)
{
    pthread_mutex_lock(&quiet_lock);
    if (quiet_depth++ == 0)
        quiet_saved = gsl_set_error_handler_off();
    pthread_mutex_unlock(&quiet_lock);
}

void sl_gsl_quiet_end(void)
{
    pthread_mutex_lock(&quiet_lock);
    if (quiet_depth > 0 && --quiet_depth == 0) {
        gsl_set_error_handler(quiet_saved);
        quiet_saved = NULL;
    }
    pthread_mutex_unlock(&quiet_lock);
}
