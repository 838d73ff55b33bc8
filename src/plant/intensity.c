/* intensity.c - the floors of one building checked against each other; see
 * intensity.h. */
#include "plant/intensity.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int cmp_d(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* The median ZPA of the compared floors (not accepted) but floor `skip`;
 * NAN when there is none. */
static double median_others(const sl_intensity_floor *f, size_t n, size_t skip)
{
    double *v = malloc((n ? n : 1) * sizeof *v);
    size_t k = 0;
    for (size_t i = 0; v && i < n; i++)
        if (i != skip && !f[i].accepted)
            v[k++] = f[i].zpa_h_ms2;
    double m = NAN;
    if (k) {
        qsort(v, k, sizeof *v, cmp_d);
        m = k % 2 ? v[k / 2] : 0.5 * (v[k / 2 - 1] + v[k / 2]);
    }
    free(v);
    return m;
}

/* The height rule between floors a and b (both elevations given): the
 * higher floor's ZPA over the lower one's (*up) and how far, in log, it
 * lies outside SL_INTENSITY_UP_MIN-MAX (at one elevation: 1/UP_MAX-UP_MAX);
 * 0 when in line or not comparable. */
static double height_excess(const sl_intensity_floor *a, const sl_intensity_floor *b, double *up)
{
    if (!isfinite(a->elevation_m) || !isfinite(b->elevation_m))
        return 0;
    const sl_intensity_floor *hi = a->elevation_m >= b->elevation_m ? a : b;
    const sl_intensity_floor *lo = hi == a ? b : a;
    double lo_b = a->elevation_m == b->elevation_m ? 1 / SL_INTENSITY_UP_MAX : SL_INTENSITY_UP_MIN;
    *up = hi->zpa_h_ms2 / lo->zpa_h_ms2;
    return *up > SL_INTENSITY_UP_MAX ? log(*up / SL_INTENSITY_UP_MAX)
           : *up < lo_b            ? log(lo_b / *up)
                                   : 0;
}

/* The median rule: how far, in log, r lies outside SL_INTENSITY_MEDIAN_MIN-MAX. */
static double median_excess(double r)
{
    return r > SL_INTENSITY_MEDIAN_MAX ? log(r / SL_INTENSITY_MEDIAN_MAX)
           : r < SL_INTENSITY_MEDIAN_MIN ? log(SL_INTENSITY_MEDIAN_MIN / r)
                                         : 0;
}

/* How floor i stands against the compared others: the number of rules it
 * breaks (the median rule, and the height rule with each other floor), the
 * largest excess, and the floor of its worst height pair (n when none). */
typedef struct standing {
    int broken;
    double excess;
    size_t worst_j;
} standing;

static standing stand(const sl_intensity_floor *f, size_t n, size_t i)
{
    standing s = {0, 0, n};
    double m = median_others(f, n, i), e, up, worst = 0;
    if (isfinite(m) && (e = median_excess(f[i].zpa_h_ms2 / m)) > 0) {
        s.broken++;
        s.excess = e;
    }
    for (size_t j = 0; j < n; j++)
        if (j != i && !f[j].accepted && (e = height_excess(&f[i], &f[j], &up)) > 0) {
            s.broken++;
            s.excess = fmax(s.excess, e);
            if (e > worst) {
                worst = e;
                s.worst_j = j;
            }
        }
    return s;
}

/* "01-ground 0.300 g at 0 m, 03-el24 0.5 g" : the compared floors but i. */
static void others_text(const sl_intensity_floor *f, size_t n, size_t i, char *buf, size_t sz)
{
    size_t used = 0;
    buf[0] = '\0';
    for (size_t j = 0; j < n && used + 1 < sz; j++) {
        if (j == i || f[j].accepted)
            continue;
        char el[48] = "";
        if (isfinite(f[j].elevation_m))
            snprintf(el, sizeof el, " at %g m", f[j].elevation_m);
        int w = snprintf(buf + used, sz - used, "%s%s %.3g g%s", used ? ", " : "", f[j].id,
                         f[j].zpa_h_ms2 / SL_G, el);
        if (w < 0 || (size_t)w >= sz - used)
            break;
        used += (size_t)w;
    }
}

/* The unit floor i's values are likely in: the other unit that brings its
 * ZPA nearest the median of the others (ref), when that lands it in line. */
static void likely_unit(const sl_intensity_floor *fl, double ref, char *buf, size_t sz)
{
    static const sl_unit cand[] = {SL_UNIT_G, SL_UNIT_MS2, SL_UNIT_CMS2, SL_UNIT_MMS2};
    double best = INFINITY, z_best = NAN;
    sl_unit u_best = SL_UNIT_NONE;
    for (size_t c = 0; c < sizeof cand / sizeof cand[0]; c++) {
        if (cand[c] == fl->units || fl->units == SL_UNIT_NONE)
            continue;
        double z = fl->zpa_h_ms2 * sl_unit_to_ms2(cand[c]) / sl_unit_to_ms2(fl->units);
        double d = fabs(log(z / ref));
        if (d < best) {
            best = d;
            z_best = z;
            u_best = cand[c];
        }
    }
    if (u_best != SL_UNIT_NONE && isfinite(ref) && median_excess(z_best / ref) == 0)
        snprintf(buf, sz, "its values are likely in %s, not %s (its ZPA would then be %.3g g)",
                 sl_unit_name(u_best), fl->units_text ? fl->units_text : sl_unit_name(fl->units),
                 z_best / SL_G);
    else
        snprintf(buf, sz, "no other unit brings it in line: check its values");
}

/* What the rules say of floor i against the compared others (the message
 * body, from "horizontal ZPA ..."). */
static void verdict_text(const sl_intensity_floor *f, size_t n, size_t i, const char *building,
                         char *buf, size_t sz)
{
    char others[600], unit[200], pair[300] = "";
    size_t j = stand(f, n, i).worst_j;
    double m = median_others(f, n, i), up;
    others_text(f, n, i, others, sizeof others);
    likely_unit(&f[i], m, unit, sizeof unit);
    if (j < n && height_excess(&f[i], &f[j], &up) > 0) {
        double dz = f[j].elevation_m - f[i].elevation_m;
        if (dz > 0)
            snprintf(pair, sizeof pair, "; %s, %g m above it, has %.3g x its ZPA", f[j].id, dz,
                     up);
        else if (dz < 0)
            snprintf(pair, sizeof pair, "; it has %.3g x the ZPA of %s, %g m below it", up,
                     f[j].id, -dz);
        else
            snprintf(pair, sizeof pair, "; %s, at its elevation, has %.3g x its ZPA", f[j].id,
                     f[j].zpa_h_ms2 / f[i].zpa_h_ms2);
    }
    char in[120];
    if (building && *building)
        snprintf(in, sizeof in, "building %s", building);
    else
        snprintf(in, sizeof in, "its building");
    snprintf(buf, sz,
             "horizontal ZPA %.3g g is %.3g x the median of the other floors of %s (%s)%s. On "
             "physical floors a floor's ZPA is %g-%g x the median of its building's others and "
             "a higher floor's %g-%g x a lower one's (docs/formats-floor.md, \"Floors of one "
             "building\"): %s",
             f[i].zpa_h_ms2 / SL_G, f[i].zpa_h_ms2 / m, in, others, pair,
             SL_INTENSITY_MEDIAN_MIN, SL_INTENSITY_MEDIAN_MAX, SL_INTENSITY_UP_MIN,
             SL_INTENSITY_UP_MAX, unit);
}

static void floor_label(const sl_intensity_floor *fl, char *buf, size_t sz)
{
    if (isfinite(fl->elevation_m))
        snprintf(buf, sz, "floor %s ('%s', el. %g m)", fl->id, fl->name, fl->elevation_m);
    else
        snprintf(buf, sz, "floor %s ('%s')", fl->id, fl->name);
}

sl_status sl_intensity_check(const sl_intensity_floor *f, size_t n, const char *building,
                             char (*warn)[SL_INTENSITY_WARN_MAX], sl_error *err)
{
    /* accepted floors: what the rules would say of them, against the others */
    for (size_t i = 0; warn && i < n; i++) {
        warn[i][0] = '\0';
        if (f[i].accepted && stand(f, n, i).broken) {
            char v[SL_INTENSITY_WARN_MAX - 80];
            verdict_text(f, n, i, building, v, sizeof v);
            snprintf(warn[i], SL_INTENSITY_WARN_MAX, "accepted by --accept-floor: %s", v);
        }
    }
    /* the floor that breaks the most rules, the furthest out among those */
    size_t top = n, compared = 0;
    standing best = {0, 0, n};
    for (size_t i = 0; i < n; i++) {
        if (f[i].accepted)
            continue;
        compared++;
        standing s = stand(f, n, i);
        if (s.broken > best.broken || (s.broken && s.broken == best.broken && s.excess > best.excess)) {
            best = s;
            top = i;
        }
    }
    if (top == n)
        return SL_OK;
    char label[300], v[1000];
    floor_label(&f[top], label, sizeof label);
    verdict_text(f, n, top, building, v, sizeof v);
    if (compared == 2) { /* two floors: either may be the one that slipped */
        size_t other = 0;
        while (other < n && (other == top || f[other].accepted))
            other++;
        char label2[300], unit2[200];
        floor_label(&f[other], label2, sizeof label2);
        likely_unit(&f[other], f[top].zpa_h_ms2, unit2, sizeof unit2);
        return sl_error_set(err, SL_EINVAL, f[top].path, 0,
                            "%s and %s (%s) are out of line with each other: %s %s; or, of %s, "
                            "%s. Check the units of both, or, if the ZPAs are right, run with "
                            "--accept-floor naming one",
                            label, label2, f[other].path, f[top].id, v, f[other].id, unit2);
    }
    return sl_error_set(err, SL_EINVAL, f[top].path, 0,
                        "%s: %s. Check the units (%s), or, if the ZPA is right, run with "
                        "--accept-floor %s",
                        label, v, f[top].units_text ? f[top].units_text : "", f[top].id);
}
