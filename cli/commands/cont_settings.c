/* SPDX-License-Identifier: BSD-3-Clause */
/* cont_settings.c — XPPAUT's AUTO options of a model file's @ lines and --opt NAME=VALUE
 * for dynkit continue (cont_settings.h). XPPAUT's manual, "AUTO" chapter, names them:
 * ntst, ncol (collocation mesh), nmax (points per branch), npr (print interval), ds,
 * dsmin, dsmax (arclength steps), parmin, parmax (the parameter's range), autoxmin..autoymax
 * (the diagram's window); names are case-insensitive, as XPPAUT reads them. */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "cont_settings.h"

const char *const cont_settings_names[] = {
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
    int k = 0;
    while (cont_settings_names[k] && !same(cont_settings_names[k], name))
        k++;
    if (!cont_settings_names[k]) {
        snprintf(err, errlen,
                 "%s: unknown setting '%s' (accepted: ntst, ncol, nmax, npr, ds, dsmin, dsmax, "
                 "parmin, parmax, par2min, par2max, autoxmin, autoxmax, autoymin, autoymax)",
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
    s->from[k] = where;
    return 0;
}

int cont_settings_fit_start(cont_settings *s, double p0, const char *par, char *note,
                            size_t notelen, char *err, size_t errlen)
{
    dyn_cont_opts *o = &s->opts;
    const char *from_min = s->from[7], *from_max = s->from[8];
    if (note && notelen)
        note[0] = 0;
    if ((from_min && !(p0 >= o->parmin)) || (from_max && !(p0 <= o->parmax))) {
        const int low = from_min && !(p0 >= o->parmin);
        snprintf(err, errlen,
                 "the start %s = %.17g is outside [parmin, parmax] = [%.17g, %.17g] (%s from "
                 "%s): give a window that contains it, or another start (--set %s=VALUE)",
                 par, p0, o->parmin, o->parmax, low ? "parmin" : "parmax",
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
                 "the start %s = %.17g is outside the default window: %s = %.17g, not %.17g, so that "
                 "[parmin, parmax] = [%.17g, %.17g] contains it (--opt %s=VALUE chooses)",
                 par, p0, below ? "parmin" : "parmax", below ? o->parmin : o->parmax, was,
                 o->parmin, o->parmax, below ? "parmin" : "parmax");
    return 0;
}

/* the name=value pairs of one @ line (text after the @) */
static int read_line(cont_settings *s, const char *line, size_t len, const char *where,
                     char *err, size_t errlen)
{
    char buf[1024];
    size_t m = 0;
    /* drop the blanks around '=' so that "ds = 0.01" reads as "ds=0.01" */
    for (size_t i = 0; i < len && m + 1 < sizeof buf; i++) {
        if (line[i] == ' ' || line[i] == '\t') {
            size_t j = i;
            while (j < len && (line[j] == ' ' || line[j] == '\t'))
                j++;
            if ((j < len && line[j] == '=') || (m > 0 && buf[m - 1] == '=')) {
                i = j - 1;
                continue;
            }
        }
        buf[m++] = line[i];
    }
    buf[m] = 0;
    for (char *tok = buf; *tok;) {
        size_t l = strcspn(tok, ", \t\r");
        const int last = tok[l] == 0;
        tok[l] = 0;
        char *eq = strchr(tok, '=');
        if (eq) {
            *eq = 0;
            int known = 0;
            for (int k = 0; cont_settings_names[k]; k++)
                known |= same(cont_settings_names[k], tok);
            if (known && cont_settings_apply(s, tok, eq + 1, where, err, errlen))
                return -1;
        }
        tok += l + (last ? 0 : 1);
    }
    return 0;
}

int cont_settings_read_file(cont_settings *s, const char *text, const char *path, char *err,
                            size_t errlen)
{
    long line = 0;
    for (const char *p = text; *p;) {
        const char *e = strchr(p, '\n');
        const size_t len = e ? (size_t)(e - p) : strlen(p);
        line++;
        size_t i = 0;
        while (i < len && (p[i] == ' ' || p[i] == '\t'))
            i++;
        if (i < len && p[i] == '@') {
            /* the setting's origin lives as long as the settings: a static copy per line
             * would not, so the file's name and the line are kept in a small pool */
            static char where[16][300];
            static int used = 0;
            char *w = where[used % 16];
            used++;
            snprintf(w, sizeof where[0], "%s:%ld", path, line);
            if (read_line(s, p + i + 1, len - i - 1, w, err, errlen))
                return -1;
        }
        p += len + (e ? 1 : 0);
    }
    return 0;
}
