/* SPDX-License-Identifier: BSD-3-Clause */
/* Values of the run options: the time span, --set/--init assignments, tolerances, output
 * times, events and positive numbers; each bad value gets a usage error naming it. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/lang.h"
#include "run/run_parse.h"
#include "util/out_file.h"

/* Split "NAME=VALUE" and read VALUE (cli_parse_value: a number or a formula of the
 * parameters); returns 0 and the parts, or -1 (why: what is wrong with VALUE, or ""). */
static int split_assignment(const char *text, char *name, size_t size, double *value,
                            char *why, size_t why_size)
{
    const char *eq = strchr(text, '=');
    why[0] = '\0';
    if (!eq || eq == text || (size_t)(eq - text) >= size)
        return -1;
    memcpy(name, text, (size_t)(eq - text));
    name[eq - text] = '\0';
    return cli_parse_value(eq + 1, value, why, why_size);
}

int cli_assignment_is_number(const assignment *as)
{
    const char *eq = strchr(as->text, '=');
    double v;
    return eq && cli_parse_number(eq + 1, &v) == 0;
}

static void list_vars(char *buf, size_t size, const dyn_var *vars, int n)
{
    size_t used = 0;
    buf[0] = '\0';
    for (int i = 0; i < n && used < size; i++)
        used += (size_t)snprintf(buf + used, size - used, "%s%s", i ? ", " : "", vars[i].name);
}

static void list_params(char *buf, size_t size, const dyn_model *m)
{
    size_t used = 0;
    buf[0] = '\0';
    for (int i = 0; i < m->n_params && used < size; i++)
        used += (size_t)snprintf(buf + used, size - used, "%s%s", i ? ", " : "",
                                 m->params[i].name);
}

int cli_parse_tspan(const char *command, const char *text, double *t0, double *t1)
{
    char first[64];
    const char *colon = strchr(text, ':');
    if (!colon || (size_t)(colon - text) >= sizeof first)
        return cli_usage_error(command, "--tspan '%s' is not accepted: give T0:T1 in s, e.g. 0:15",
                               text);
    memcpy(first, text, (size_t)(colon - text));
    first[colon - text] = '\0';
    if (cli_parse_number(first, t0) || cli_parse_number(colon + 1, t1))
        return cli_usage_error(command,
                               "--tspan '%s' is not accepted: T0 and T1 must be finite numbers "
                               "(T0:T1 in s, e.g. 0:15)",
                               text);
    if (!(*t1 > *t0))
        return cli_usage_error(command, "--tspan '%s' is not accepted: T1 must be greater than T0",
                               text);
    return CLI_OK;
}

/* The unknown NAME of --set (parameters) or --init (states): the nearest name of the same
 * kind as a likely typo, or a name of the other kind given to the wrong option. */
static int unknown_name(const char *command, const cli_run *run, int is_param, const char *name)
{
    const dyn_model *m = run->model;
    const char *names[128];
    char list[512];
    int n = 0;
    if (is_param) {
        for (int i = 0; i < m->n_params && n < 128; i++)
            names[n++] = m->params[i].name;
        list_params(list, sizeof list, m);
    } else {
        for (int i = 0; i < m->n_states && n < 128; i++)
            names[n++] = m->states[i].name;
        list_vars(list, sizeof list, m->states, m->n_states);
    }
    const char *opt = is_param ? "--set" : "--init";
    const char *what = is_param ? "parameter" : "state";
    if (is_param ? dyn_model_state_index(m, name) >= 0 : dyn_model_param_index(m, name) >= 0)
        return cli_usage_error(command, "%s: %s is a %s of model %s: give it with %s (%ss: %s)",
                               opt, name, is_param ? "state" : "parameter", m->name,
                               is_param ? "--init" : "--set", what, list);
    const char *near = dyn_lang_nearest(name, names, n);
    if (near)
        return cli_usage_error(command,
                               "%s: model %s has no %s '%s' (did you mean '%s'? accepted: %s)",
                               opt, m->name, what, name, near, list);
    return cli_usage_error(command, "%s: model %s has no %s '%s' (accepted: %s)", opt, m->name,
                           what, name, list);
}

int cli_apply_assignment(const char *command, cli_run *run, const assignment *as)
{
    char name[64];
    double value;
    const dyn_model *m = run->model;
    const char *opt = as->is_param ? "--set" : "--init";
    char why[400];
    if (split_assignment(as->text, name, sizeof name, &value, why, sizeof why))
        return cli_usage_error(command,
                               "%s '%s' is not accepted%s%s: give NAME=VALUE, VALUE a finite "
                               "number or a formula of the parameters (200-W*cos(0.3))",
                               opt, as->text, why[0] ? ": " : "", why);
    if (as->is_param) {
        int i = dyn_model_param_index(m, name);
        if (i < 0)
            return unknown_name(command, run, 1, name);
        if (cli_param_is_size(m, name) && value != dyn_model_get_param(m, run->par, i))
            return cli_usage_error(command,
                                   "--set %s is not accepted: %s is the size of the model; "
                                   "choose it with the model, e.g. %s:%g",
                                   as->text, name, m->name, value);
        dyn_model_set_param(m, run->par, i, value);
    } else {
        int i = dyn_model_state_index(m, name);
        if (i < 0)
            return unknown_name(command, run, 0, name);
        run->y0[i] = value;
    }
    return CLI_OK;
}

/* A tolerance: one number >= 0 (*scalar), or one per state, comma-separated (*vec, owned). */
int cli_parse_tolerance(const char *command, const char *opt, const char *text, int n,
                           double *scalar, double **vec)
{
    free(*vec);
    *vec = NULL;
    if (!strchr(text, ',')) {
        if (cli_parse_number(text, scalar) || !(*scalar > 0))
            return cli_usage_error(command,
                                   "%s '%s' is not accepted: give a number > 0 (e.g. 1e-6), or "
                                   "one per state separated by commas",
                                   opt, text);
        return CLI_OK;
    }
    double *v = calloc((size_t)n, sizeof *v);
    if (!v)
        return cli_usage_error(command, "out of memory");
    const char *p = text;
    int count = 0;
    while (*p) {
        char item[64];
        const char *comma = strchr(p, ',');
        size_t len = comma ? (size_t)(comma - p) : strlen(p);
        if (len >= sizeof item || count >= n)
            break;
        memcpy(item, p, len);
        item[len] = '\0';
        if (cli_parse_number(item, &v[count]) || !(v[count] >= 0)) {
            free(v);
            return cli_usage_error(command,
                                   "%s '%s' is not accepted: '%s' is not a number >= 0", opt,
                                   text, item);
        }
        count++;
        if (!comma) {
            p += len;
            break;
        }
        p = comma + 1;
    }
    if (count != n || *p) {
        free(v);
        return cli_usage_error(command,
                               "%s '%s' is not accepted: give one value, or %d values (one per "
                               "state) separated by commas",
                               opt, text, n);
    }
    *vec = v;
    return CLI_OK;
}

/* Append a time to a growing list. */
static int push_time(double **times, long *count, long *cap, double t)
{
    if (*count == *cap) {
        long ncap = *cap ? 2 * *cap : 64;
        double *nt = realloc(*times, (size_t)ncap * sizeof *nt);
        if (!nt)
            return -1;
        *times = nt;
        *cap = ncap;
    }
    (*times)[(*count)++] = t;
    return 0;
}

/* The longest line of a --times file (a time is a number: far less). */
#define TIMES_MAX_LINE 65536

/* One line of f (without its LF) into *line (grown as needed). Returns 1 for a line, 0 at
 * the end, -1 with *why for what is no text file of times: a NUL byte, UTF-16, CR-only line
 * ends, a line longer than TIMES_MAX_LINE, a read error (a directory), out of memory. */
static int read_time_line(FILE *f, char **line, const char **why)
{
    size_t len = 0;
    int c;
    char *buf = *line; /* TIMES_MAX_LINE + 1 bytes once allocated */
    for (;;) {
        c = fgetc(f);
        if (c == EOF || c == '\n')
            break;
        if (c == '\0') {
            const int bom = buf && len >= 2 &&
                            (((unsigned char)buf[0] == 0xFF && (unsigned char)buf[1] == 0xFE) ||
                             ((unsigned char)buf[0] == 0xFE && (unsigned char)buf[1] == 0xFF));
            *why = bom ? "the file is UTF-16 encoded: save it as UTF-8 or ASCII text"
                       : "a NUL byte: this is no text file (UTF-16 text has them: save it as "
                         "UTF-8)";
            return -1;
        }
        if (len >= TIMES_MAX_LINE) {
            *why = "the line is longer than 65536 bytes";
            return -1;
        }
        if (!buf) {
            buf = malloc(TIMES_MAX_LINE + 1);
            if (!buf) {
                *why = "out of memory";
                return -1;
            }
            *line = buf;
        }
        buf[len++] = (char)c;
    }
    if (c == EOF && ferror(f)) {
        *why = strerror(errno);
        return -1;
    }
    if (c == EOF && len == 0)
        return 0;
    if (!buf) {
        buf = malloc(TIMES_MAX_LINE + 1);
        if (!buf) {
            *why = "out of memory";
            return -1;
        }
        *line = buf;
    }
    buf[len] = '\0';
    if (len >= 2 && (((unsigned char)buf[0] == 0xFF && (unsigned char)buf[1] == 0xFE) ||
                     ((unsigned char)buf[0] == 0xFE && (unsigned char)buf[1] == 0xFF))) {
        *why = "the file is UTF-16 encoded: save it as UTF-8 or ASCII text";
        return -1;
    }
    char *cr = memchr(buf, '\r', len);
    if (cr && cr != buf + len - 1) {
        *why = "a carriage return inside the line: lines end with CR only (old Mac style); "
               "save the file with LF or CRLF line ends";
        return -1;
    }
    return 1;
}

/* --times: "t1,t2,..." or "@FILE" (one time per line; blank lines and lines starting with
 * '#' are skipped). The times must not decrease. */
int cli_parse_times(const char *command, const char *text, cli_run *run)
{
    long cap = 0;
    free(run->times);
    run->times = NULL;
    run->n_times = 0;
    if (text[0] == '@') {
        cli_input_note(text + 1, "the --times file");
        FILE *f = fopen(text + 1, "r");
        if (!f)
            return cli_usage_error(command, "--times: cannot read '%s': %s", text + 1,
                                   strerror(errno));
        char *line = NULL, shown[96];
        long lineno = 0;
        int rc = CLI_OK, got;
        const char *why = NULL;
        while (rc == CLI_OK && (got = read_time_line(f, &line, &why)) == 1) {
            lineno++;
            char *p = line, *e = line + strlen(line);
            if (lineno == 1 && strncmp(p, "\xEF\xBB\xBF", 3) == 0)
                p += 3; /* UTF-8 byte order mark */
            while (*p == ' ' || *p == '\t')
                p++;
            while (e > p && (e[-1] == '\r' || e[-1] == ' ' || e[-1] == '\t'))
                *--e = '\0';
            if (!*p || *p == '#')
                continue;
            double t;
            if (cli_parse_number(p, &t))
                rc = cli_usage_error(command, "--times: line %ld of %s ('%s') is not a time in s",
                                     lineno, text + 1, dyn_text_escaped(p, shown, sizeof shown));
            else if (push_time(&run->times, &run->n_times, &cap, t)) {
                cli_error("--times %s: out of memory", text + 1);
                rc = CLI_FAILED;
            }
        }
        if (rc == CLI_OK && got < 0) {
            if (why && strcmp(why, "out of memory") == 0) {
                cli_error("--times %s: out of memory", text + 1);
                rc = CLI_FAILED;
            } else {
                rc = cli_usage_error(command, "--times: %s, line %ld: %s", text + 1, lineno + 1,
                                     why ? why : strerror(errno));
            }
        }
        free(line);
        fclose(f);
        if (rc != CLI_OK)
            return rc;
    } else {
        const char *p = text;
        while (1) {
            char item[64];
            const char *comma = strchr(p, ',');
            size_t len = comma ? (size_t)(comma - p) : strlen(p);
            double t;
            if (len >= sizeof item)
                return cli_usage_error(command, "--times: '%.20s...' is too long", p);
            memcpy(item, p, len);
            item[len] = '\0';
            if (cli_parse_number(item, &t))
                return cli_usage_error(command,
                                       "--times '%s' is not accepted: '%s' is not a time in s "
                                       "(give times separated by commas, or @FILE)",
                                       text, item);
            if (push_time(&run->times, &run->n_times, &cap, t))
                return cli_usage_error(command, "out of memory");
            if (!comma)
                break;
            p = comma + 1;
        }
    }
    if (run->n_times == 0)
        return cli_usage_error(command, "--times %s: no times given", text);
    for (long k = 1; k < run->n_times; k++)
        if (run->times[k] < run->times[k - 1])
            return cli_usage_error(command,
                                   "--times: the times must not decrease (%s follows %s)",
                                   CLI_NUM(run->times[k]), CLI_NUM(run->times[k - 1]));
    return CLI_OK;
}

/* --event NAME[:stop|:continue]: the model's event as a copy, terminal as the model declares
 * it (an .ode file's `#: event ... stop`, a C model's .terminal), or as :stop / :continue
 * say. */
int cli_add_event(const char *command, const char *text, cli_run *run)
{
    const dyn_model *m = run->model;
    char name[64], list[512];
    const char *colon = strchr(text, ':');
    size_t len = colon ? (size_t)(colon - text) : strlen(text);
    int terminal = -1; /* the model's */
    if (colon) {
        if (strcmp(colon + 1, "stop") == 0)
            terminal = 1;
        else if (strcmp(colon + 1, "continue") == 0)
            terminal = 0;
        else
            return cli_usage_error(command,
                                   "--event '%s' is not accepted: give NAME, NAME:stop or "
                                   "NAME:continue",
                                   text);
    }
    size_t used = 0;
    list[0] = '\0';
    for (int i = 0; i < m->n_events && used < sizeof list; i++)
        used += (size_t)snprintf(list + used, sizeof list - used, "%s%s", i ? ", " : "",
                                 m->events[i].name);
    if (len >= sizeof name || m->n_events <= 0)
        return cli_usage_error(command, "--event: model %s has no event '%.*s' (%s%s)", m->name,
                               (int)(len < 60 ? len : 60), text,
                               m->n_events > 0 ? "accepted: " : "it has no events",
                               m->n_events > 0 ? list : "");
    memcpy(name, text, len);
    name[len] = '\0';
    int found = -1;
    for (int i = 0; i < m->n_events; i++)
        if (strcmp(m->events[i].name, name) == 0)
            found = i;
    if (found < 0)
        return cli_usage_error(command, "--event: model %s has no event '%s' (accepted: %s)",
                               m->name, name, list);
    dyn_event *ev = realloc(run->events, (size_t)(run->n_events + 1) * sizeof *ev);
    if (!ev)
        return cli_usage_error(command, "out of memory");
    run->events = ev;
    ev[run->n_events] = m->events[found];
    if (terminal >= 0)
        ev[run->n_events].terminal = terminal;
    run->n_events++;
    return CLI_OK;
}

/* A step-like option: a finite number > 0. */
int cli_parse_positive(const char *command, const char *opt, const char *text, double *out)
{
    if (cli_parse_number(text, out) || !(*out > 0))
        return cli_usage_error(command,
                               "%s '%s' is not accepted: give a time in s, a finite number > 0",
                               opt, text);
    return CLI_OK;
}
