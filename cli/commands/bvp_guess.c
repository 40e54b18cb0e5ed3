/* SPDX-License-Identifier: BSD-3-Clause */
/* bvp_guess.c — dynkit bvp --guess FILE (bvp_guess.h): a CSV table (RFC 4180 without
 * quoted fields: a header line of names, then numbers) read as the first guess of a
 * boundary-value problem, each state's column found by its name. docs/analysis.md,
 * "Boundary-value problems". */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands/bvp_guess.h"

#define GUESS_MAX_COLS 4096

/* the fields of line (modified in place: commas become NULs) into f; their number */
static int split(char *line, char **f, int max)
{
    int k = 0;
    line[strcspn(line, "\r\n")] = '\0';
    for (char *p = line;; p++) {
        if (k < max)
            f[k] = p;
        k++;
        p += strcspn(p, ",");
        if (*p != ',')
            break;
        *p = '\0';
    }
    for (int i = 0; i < k && i < max; i++) { /* blanks around a field */
        while (*f[i] == ' ' || *f[i] == '\t')
            f[i]++;
        size_t len = strlen(f[i]);
        while (len && (f[i][len - 1] == ' ' || f[i][len - 1] == '\t'))
            f[i][--len] = '\0';
    }
    return k;
}

int bvp_guess_read(const char *path, const dyn_model *m, double **t, double **u, long *rows,
                   char *err, size_t errlen)
{
    *t = *u = NULL;
    *rows = 0;
    FILE *in = fopen(path, "r");
    if (!in) {
        snprintf(err, errlen, "%s: %s", path, strerror(errno));
        return -1;
    }
    const int n = m->n_states;
    char **f = malloc(GUESS_MAX_COLS * sizeof *f);
    int *col = malloc((size_t)n * sizeof *col);
    char *line = NULL;
    size_t cap = 0;
    long lineno = 1, room = 0;
    int st = -1, cols = 0;
    if (!f || !col) {
        snprintf(err, errlen, "out of memory");
        goto done;
    }
    if (getline(&line, &cap, in) < 0) {
        snprintf(err, errlen, "%s: empty; a first guess is a CSV table: a header line t,NAME,"
                 "... then rows of numbers (dynkit bvp's output)", path);
        goto done;
    }
    cols = split(line, f, GUESS_MAX_COLS);
    if (cols > GUESS_MAX_COLS || strcmp(f[0], "t") != 0) {
        snprintf(err, errlen, "%s:1: the header must begin with t and have at most %d "
                 "columns (a CSV table of t and the states: dynkit bvp's output)", path,
                 GUESS_MAX_COLS);
        goto done;
    }
    for (int i = 0; i < n; i++) {
        col[i] = -1;
        for (int k = 1; k < cols; k++)
            if (strcmp(f[k], m->states[i].name) == 0)
                col[i] = k;
        if (col[i] < 0) {
            snprintf(err, errlen, "%s:1: no column for the state %s (the table needs t and "
                     "every state of the model)", path, m->states[i].name);
            goto done;
        }
    }
    for (;;) {
        if (getline(&line, &cap, in) < 0)
            break;
        lineno++;
        if (line[strspn(line, " \t\r\n")] == '\0')
            continue;
        const int k = split(line, f, GUESS_MAX_COLS);
        if (k != cols) {
            snprintf(err, errlen, "%s:%ld: %d fields where the header has %d", path, lineno, k,
                     cols);
            goto done;
        }
        if (*rows == room) {
            room = room ? 2 * room : 256;
            double *nt = realloc(*t, (size_t)room * sizeof(double));
            if (nt)
                *t = nt;
            double *nu = realloc(*u, (size_t)room * n * sizeof(double));
            if (nu)
                *u = nu;
            if (!nt || !nu) {
                snprintf(err, errlen, "out of memory");
                goto done;
            }
        }
        for (int i = -1; i < n; i++) {
            const int c = i < 0 ? 0 : col[i];
            char *end;
            errno = 0;
            const double v = strtod(f[c], &end);
            if (end == f[c] || *end || errno == ERANGE || !isfinite(v)) {
                snprintf(err, errlen, "%s:%ld: column %s: '%.40s' is not a number", path,
                         lineno, i < 0 ? "t" : m->states[i].name, f[c]);
                goto done;
            }
            if (i < 0)
                (*t)[*rows] = v;
            else
                (*u)[(size_t)*rows * n + i] = v;
        }
        if (*rows > 0 && !((*t)[*rows] >= (*t)[*rows - 1])) {
            snprintf(err, errlen, "%s:%ld: t goes back (the rows must be in increasing t)",
                     path, lineno);
            goto done;
        }
        ++*rows;
    }
    if (*rows < 2 || !((*t)[*rows - 1] > (*t)[0])) {
        snprintf(err, errlen, "%s: %ld row%s: a first guess needs at least two rows over an "
                 "interval of t", path, *rows, *rows == 1 ? "" : "s");
        goto done;
    }
    st = 0;
done:
    if (st) {
        free(*t);
        free(*u);
        *t = *u = NULL;
        *rows = 0;
    }
    free(line);
    free(f);
    free(col);
    fclose(in);
    return st;
}
