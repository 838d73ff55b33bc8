/* fftw_safe.c - FFTW's planner lock, installed once (fftw_safe.h). */
#include "core/fftw_safe.h"

#include <fftw3.h>
#include <pthread.h>

static pthread_once_t planner_once = PTHREAD_ONCE_INIT;

void sl_fftw_thread_safe(void)
{
    pthread_once(&planner_once, fftw_make_planner_thread_safe);
}
