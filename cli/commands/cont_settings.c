/* SPDX-License-Identifier: BSD-3-Clause */
/* cont_settings.c — XPPAUT's AUTO options of a model file's @ lines and --opt NAME=VALUE
 * for dynkit continue (cont_settings.h). XPPAUT's manual, "AUTO" chapter, names them:
 * ntst, ncol (collocation mesh), nmax (points per branch), npr (print interval), ds,
 * dsmin, dsmax (arclength steps), parmin, parmax (the parameter's range), autoxmin..autoymax
 * (the diagram's window), autovar (the state on its y axis); names are case-insensitive, as XPPAUT reads them. The file's
 * @ lines are read by the model file's parser (dyn_ode_auto_options, dynkit/lang.h). */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "cont_settings.h"
#include "dynkit/io.h"
#include "dynkit/lang.h"

static const char *const cont_settings_names[] = {
    "ntst", "ncol", "nmax", "npr", "ds", "dsmin", "dsmax", "parmin", "parmax",
    "autoxmin", "autoxmax", "autoymin", "autoymax", "par2min", "par2max", NULL};

static int same(const char *a, const char *b)
{
    for (; *a && *b; a++, b++)
        if (tolower((unsigned char)*a) != tolower((unsigned char)*b))
            return 0;
    return *a == *b;
}

int cont_settings_apply(cont_settings *s, const char *name, const char *value, const char *where,
                        char *err, size_t errlen)
{
    if (same(name, "autovar")) { /* a state's name, checked by the caller */
        snprintf(s->autovar, sizeof s->autovar, "%s", value);
        snprintf(s->autovar_from, sizeof s->autovar_from, "%s", where);
        return 0;
    }
    int k = 0;
    while (cont_settings_names[k] && !same(cont_settings_names[k], name))
        k++;
    if (!cont_settings_names[k]) {
        snprintf(err, errlen,
                 "%s: unknown setting '%s' (accepted: ntst, ncol, nmax, npr, ds, dsmin, dsmax, "
                 "parmin, parmax, par2min, par2max, autoxmin, autoxmax, autoymin, autoymax, "
                 "autovar)",
                 where, name);
        return -1;
    }
    double v;
    if (cli_parse_number(value, &v)) {
        snprintf(err, errlen, "%s: %s=%s: give a finite number", where, name, value);
        return -1;
    }
    dyn_cont_opts *o = &s->opts;
    if (k <= 3) {
        if (!(v >= 1.0 && v <= 1e8) || v != floor(v)) {
            snprintf(err, errlen, "%s: %s=%s: give a whole number from 1 to 100000000", where,
                     name, value);
            return -1;
        }
        if (k == 0)
            o->ntst = (int)v;
        else if (k == 1)
            o->ncol = (int)v;
        else if (k == 2)
            o->nmax = (long)v;
        else
            o->npr = (long)v;
    } else if (k == 4) {
        if (v == 0.0) {
            snprintf(err, errlen, "%s: ds=%s: give a step other than 0 (its sign is the "
                     "direction)", where, value);
            return -1;
        }
        o->ds = v;
    } else if (k == 5 || k == 6) {
        if (!(v > 0.0)) {
            snprintf(err, errlen, "%s: %s=%s: give a number > 0", where, name, value);
            return -1;
        }
        *(k == 5 ? &o->dsmin : &o->dsmax) = v;
    } else if (k == 7) {
        o->parmin = v;
    } else if (k == 8) {
        o->parmax = v;
    } else if (k <= 12) {
        s->window[k - 9] = v;
    } else if (k == 13) {
        o->par2min = v;
    } else {
        o->par2max = v;
    }
    snprintf(s->from[k], sizeof s->from[k], "%s", where);
    return 0;
}

int cont_settings_fit_start(cont_settings *s, double p0, const char *par, char *note,
                            size_t notelen, char *err, size_t errlen)
{
    dyn_cont_opts *o = &s->opts;
    const char *from_min = s->from[7][0] ? s->from[7] : NULL;
    const char *from_max = s->from[8][0] ? s->from[8] : NULL;
    if (note && notelen)
        note[0] = 0;
    if ((from_min && !(p0 >= o->parmin)) || (from_max && !(p0 <= o->parmax))) {
        const int low = from_min && !(p0 >= o->parmin);
        snprintf(err, errlen,
                 "the start %s = %s is outside [parmin, parmax] = [%s, %s] (%s from "
                 "%s): give a window that contains it, or another start (--set %s=VALUE)",
                 par, dyn_shortest(p0).s, dyn_shortest(o->parmin).s, dyn_shortest(o->parmax).s,
                 low ? "parmin" : "parmax",
                 low ? from_min : from_max, par);
        return -1;
    }
    dyn_cont_opts defaults;
    dyn_cont_opts_default(&defaults, o->ip);
    const double width = defaults.parmax - defaults.parmin;
    const int below = !from_min && p0 < o->parmin, above = !from_max && p0 > o->parmax;
    if (!below && !above)
        return 0;
    const double was = below ? o->parmin : o->parmax;
    if (below)
        o->parmin = p0 - fmax(o->parmax - p0, width);
    else
        o->parmax = p0 + fmax(p0 - o->parmin, width);
    if (note && notelen)
        snprintf(note, notelen,
                 "the start %s = %s is outside the default window: %s = %s, not %s, so that "
                 "[parmin, parmax] = [%s, %s] contains it (--opt %s=VALUE chooses)",
                 par, dyn_shortest(p0).s, below ? "parmin" : "parmax",
                 dyn_shortest(below ? o->parmin : o->parmax).s, dyn_shortest(was).s,
                 dyn_shortest(o->parmin).s, dyn_shortest(o->parmax).s,
                 below ? "parmin" : "parmax");
    return 0;
}

typedef struct file_read {
    cont_settings *s;
    const char *path;
    char *err;
    size_t errlen;
    int bad;
} file_read;

/* one setting of the file, as the model file's parser found it */
static void from_file(const char *name, const char *value, int line, int col, void *ctx)
{
    file_read *r = ctx;
    if (r->bad)
        return;
    char where[600];
    snprintf(where, sizeof where, "%s:%d:%d", r->path, line, col);
    r->bad = cont_settings_apply(r->s, name, value, where, r->err, r->errlen) != 0;
}

int cont_settings_read_file(cont_settings *s, const char *text, size_t len, const char *path,
                            char *err, size_t errlen)
{
    file_read r = {s, path, err, errlen, 0};
    dyn_lang_diag diag;
    if (dyn_ode_auto_options(path, text, len, from_file, &r, &diag)) {
        char msg[2048];
        snprintf(err, errlen, "%s", dyn_lang_diag_format(&diag, msg, sizeof msg));
        return -1;
    }
    return r.bad ? -1 : 0;
}
