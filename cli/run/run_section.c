/* SPDX-License-Identifier: BSD-3-Clause */
/* A run's Poincaré map: XPPAUT's @ poimap, poivar, poipln, poisgn, poistop (its manual,
 * "Numerics: Poincare map", and integrate.c's conventions), or --section on the command
 * line. The section is an event of the run (dyn_event), located by the driver on the dense
 * output by Brent's method (solve.h): a state or an output crossing a value, t reaching a
 * multiple of a period (a stroboscope), or a state's rate of change crossing zero (its
 * maxima and minima). Its rows replace the samples (cmd_run.c). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "run/run_parse.h"

/* What the section's g reads: one run's section at a time (the tool makes one run with a
 * section per process). */
static struct {
    const cli_run *run;
    double *buf; /* (n_states + n_outputs) */
} the_section;

static double g_state(double t, const double *y, void *par)
{
    (void)t;
    (void)par;
    const cli_run *run = the_section.run;
    return y[run->section_var] - run->section.plane;
}

static double g_output(double t, const double *y, void *par)
{
    const cli_run *run = the_section.run;
    const dyn_model *m = run->model;
    if (m->compute_outputs(t, y, par, the_section.buf))
        return NAN;
    return the_section.buf[run->section_var - m->n_states] - run->section.plane;
}

/* t - k T for the nearest k: rises through zero at each multiple of T (and falls by T
 * half-way, which a rising section does not see) */
static double g_time(double t, const double *y, void *par)
{
    (void)y;
    (void)par;
    const double T = the_section.run->section.plane;
    return t - T * nearbyint(t / T);
}

/* the rate of change of the state: falls through zero at its maxima, rises at its minima */
static double g_rate(double t, const double *y, void *par)
{
    const cli_run *run = the_section.run;
    if (run->model->rhs(t, y, the_section.buf, par))
        return NAN;
    return the_section.buf[run->section_var];
}

int cli_section_event(const cli_run *run, dyn_event *ev)
{
    const dyn_model *m = run->model;
    memset(ev, 0, sizeof *ev);
    if (run->section.kind == DYN_POINCARE_NONE)
        return 0;
    free(the_section.buf);
    the_section.run = run;
    the_section.buf = calloc((size_t)(m->n_states + m->n_outputs + 1), sizeof(double));
    if (!the_section.buf)
        return -1;
    ev->name = "(section)"; /* no model names an event so */
    ev->description = "the run's Poincaré section";
    ev->terminal = run->section.stop;
    ev->direction = run->section.sign;
    if (run->section.kind == DYN_POINCARE_EXTREMUM) {
        ev->g = g_rate;
        ev->direction = -run->section.sign; /* maxima: the rate falls through zero */
    } else if (run->section_var < 0) {
        ev->g = g_time;
        ev->direction = 1;
    } else {
        ev->g = run->section_var < m->n_states ? g_state : g_output;
    }
    return 1;
}

double cli_section_time(const cli_run *run, double t)
{
    if (run->section.kind != DYN_POINCARE_EXTREMUM && run->section_var < 0) {
        const double T = run->section.plane;
        return T * nearbyint(t / T); /* XPPAUT writes the multiple of the period itself */
    }
    return t;
}

/* The index of name: a state, n_states + an output, -1 for t; -2 when none. */
static int variable_index(const dyn_model *m, const char *name)
{
    if (strcmp(name, "t") == 0)
        return -1;
    const int i = dyn_model_state_index(m, name);
    if (i >= 0)
        return i;
    const int j = dyn_model_output_index(m, name);
    return j >= 0 ? m->n_states + j : -2;
}

/* Check the section of run (from the model or --section; text is the option as given, or
 * NULL) and resolve its variable. */
static int resolve(const char *command, cli_run *run, const char *text)
{
    const dyn_model *m = run->model;
    const dyn_poincare *s = &run->section;
    const char *what = text ? "--section" : "the model's @ poimap: poivar";
    run->section_var = variable_index(m, s->var);
    if (run->section_var == -2)
        return cli_usage_error(command,
                               "%s '%s': model %s has no state or output '%s' (give a name "
                               "'dynkit info %s' lists, or t)",
                               what, text ? text : s->var, m->name, s->var, m->name);
    if (s->kind == DYN_POINCARE_EXTREMUM && run->section_var < 0)
        return cli_usage_error(command, "%s '%s': the maxima and minima are a state's, not t's",
                               what, text ? text : s->var);
    if (s->kind == DYN_POINCARE_EXTREMUM && run->section_var >= m->n_states)
        return cli_usage_error(command,
                               "%s '%s': the maxima and minima are found where the state's "
                               "rate of change vanishes: name a state, not the output '%s' "
                               "(or a section of it: --section %s=VALUE)",
                               what, text ? text : s->var, s->var, s->var);
    if (s->kind != DYN_POINCARE_EXTREMUM && run->section_var < 0 && !(s->plane > 0))
        return cli_usage_error(command,
                               "%s '%s': a section in t needs a period > 0 (t = k*T), not %g",
                               what, text ? text : "t", s->plane);
    return CLI_OK;
}

int cli_parse_section(const char *command, const char *text, cli_run *run)
{
    static const char accepted[] =
        "accepted: NAME=VALUE[:+|:-|:both][:stop] (NAME crosses VALUE rising, falling or "
        "both ways), t=T (every T), max:NAME, min:NAME, extrema:NAME, period:NAME=VALUE, "
        "or none";
    dyn_poincare s = {DYN_POINCARE_SECTION, NULL, 0.0, 1, 0};
    if (strcmp(text, "none") == 0) {
        run->section.kind = DYN_POINCARE_NONE;
        run->section_given = 1;
        return CLI_OK;
    }
    char buf[256];
    if (strlen(text) >= sizeof buf)
        return cli_usage_error(command, "--section: too long (%s)", accepted);
    strcpy(buf, text);
    char *p = buf;
    if (strncmp(p, "max:", 4) == 0 || strncmp(p, "min:", 4) == 0 ||
        strncmp(p, "extrema:", 8) == 0) {
        s.kind = DYN_POINCARE_EXTREMUM;
        s.sign = p[1] == 'a' ? 1 : p[1] == 'i' ? -1 : 0;
        p = strchr(p, ':') + 1;
    } else if (strncmp(p, "period:", 7) == 0) {
        s.kind = DYN_POINCARE_PERIOD;
        p += 7;
    }
    /* the suffixes :+ :- :both :stop */
    char *colon;
    while ((colon = strrchr(p, ':')) != NULL) {
        const char *suf = colon + 1;
        if (strcmp(suf, "stop") == 0)
            s.stop = 1;
        else if (strcmp(suf, "+") == 0 && s.kind != DYN_POINCARE_EXTREMUM)
            s.sign = 1;
        else if (strcmp(suf, "-") == 0 && s.kind != DYN_POINCARE_EXTREMUM)
            s.sign = -1;
        else if (strcmp(suf, "both") == 0 && s.kind != DYN_POINCARE_EXTREMUM)
            s.sign = 0;
        else
            return cli_usage_error(command, "--section '%s': ':%s' is not accepted (%s)", text,
                                   suf, accepted);
        *colon = '\0';
    }
    char *eq = strchr(p, '=');
    if (s.kind == DYN_POINCARE_EXTREMUM ? eq != NULL : eq == NULL)
        return cli_usage_error(command, "--section '%s' is not accepted (%s)", text, accepted);
    if (eq) {
        *eq = '\0';
        if (cli_parse_number(eq + 1, &s.plane))
            return cli_usage_error(command, "--section '%s': '%s' is not a number (%s)", text,
                                   eq + 1, accepted);
    }
    if (!*p)
        return cli_usage_error(command, "--section '%s': no variable named (%s)", text,
                               accepted);
    /* the name lives in argv; keep a copy with the run */
    free(run->section_name);
    if (!(run->section_name = malloc(strlen(p) + 1)))
        return cli_usage_error(command, "out of memory");
    strcpy(run->section_name, p);
    s.var = run->section_name;
    run->section = s;
    run->section_given = 1;
    return resolve(command, run, text);
}

int cli_section_from_model(const char *command, cli_run *run)
{
    if (run->section_given || run->model->poincare.kind == DYN_POINCARE_NONE)
        return CLI_OK;
    run->section = run->model->poincare;
    if (!run->section.var)
        return cli_usage_error(command, "model %s asks for a Poincaré map without its variable",
                               run->model->name);
    return resolve(command, run, NULL);
}

void cli_section_free(cli_run *run)
{
    free(run->section_name);
    run->section_name = NULL;
    if (the_section.run == run) {
        free(the_section.buf);
        the_section.buf = NULL;
        the_section.run = NULL;
    }
}
