/* plant_progress.c - progress over the whole plant; see plant_progress.h. */
#include "plant_progress.h"

#include <stdarg.h>
#include <stdio.h>
#include <time.h>
#include <unistd.h>

#include "cli.h"
#include "plant/cache.h"

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void hms(double s, char *buf, size_t n)
{
    long t = s < 0 ? 0 : (long)(s + 0.5);
    if (t >= 3600)
        snprintf(buf, n, "%ld:%02ld:%02ld", t / 3600, t / 60 % 60, t % 60);
    else
        snprintf(buf, n, "%ld:%02ld", t / 60, t % 60);
}

/* "3/8 floors done (1 reused), 150 sets, elapsed 0:12, ETA 0:30" */
static void summary(const plant_progress *pp, char *buf, size_t n)
{
    char el[32], eta[32];
    double t = now_s() - pp->t0;
    hms(t, el, sizeof el);
    if (pp->cost_done > 0)
        hms(pp->time_done / pp->cost_done * pp->cost_left, eta, sizeof eta);
    else
        snprintf(eta, sizeof eta, "-");
    snprintf(buf, n, "%zu/%zu floors done (%zu reused), %zu sets, elapsed %s, ETA %s", pp->done,
             pp->total, pp->reused, pp->sets, el, eta);
}

void plant_progress_start(plant_progress *pp, int quiet, size_t total, double cost_total)
{
    *pp = (plant_progress){.quiet = quiet, .tty = isatty(STDERR_FILENO), .total = total,
                           .t0 = now_s(), .cost_left = cost_total};
}

void plant_progress_floor(plant_progress *pp, size_t i, const char *label, double cost)
{
    pp->floor = (run_progress){pp->quiet || pp->tty, i, pp->total, label, NULL, -100};
    pp->floor_t0 = now_s();
    pp->floor_cost = cost;
}

void plant_progress_cb(void *ctx, const char *step, size_t done, size_t total)
{
    plant_progress *pp = ctx;
    if (pp->cache_dir && pp->lock_hash)
        sl_cache_lock_touch(pp->cache_dir, pp->lock_hash);
    if (pp->quiet)
        return;
    if (!pp->tty) {
        run_progress_cb(&pp->floor, step, done, total);
        return;
    }
    char s[256];
    summary(pp, s, sizeof s);
    fprintf(stderr, "\r\033[Krun: %s | floor %zu/%zu '%s': %s %zu/%zu", s, pp->floor.floor,
            pp->total, pp->floor.name, step, done, total);
    fflush(stderr);
}

void plant_progress_msg(plant_progress *pp, const char *fmt, ...)
{
    if (pp->quiet)
        return;
    if (pp->tty)
        fputs("\r\033[K", stderr);
    va_list ap;
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
}

void plant_progress_done(plant_progress *pp, size_t i, const char *label, const sl_analysis *a,
                         int reused, size_t n_mu)
{
    pp->done++;
    pp->sets += a->n_sets;
    pp->cost_left -= pp->floor_cost;
    if (reused) {
        pp->reused++;
    } else {
        pp->cost_done += pp->floor_cost;
        pp->time_done += now_s() - pp->floor_t0;
    }
    if (pp->quiet)
        return;
    char s[256];
    summary(pp, s, sizeof s);
    if (pp->tty) {
        fprintf(stderr, "\r\033[Krun: %s", s);
        fflush(stderr);
        return;
    }
    if (!reused)
        run_report_floor(i, pp->total, label, a, n_mu);
    cli_msg("run: floor %zu/%zu '%s' %s; %s", i, pp->total, label,
            reused ? "reused from the cache" : "computed", s);
}

void plant_progress_end(plant_progress *pp)
{
    if (!pp->quiet && pp->tty) {
        fputs("\r\033[K", stderr);
        fflush(stderr);
    }
}
