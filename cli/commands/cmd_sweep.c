/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit sweep MODEL [run options] --vary/--sample/--from ... --reduce LIST: many runs of one
 * model, one row per run (docs/sweeps.md). The run table comes from --vary (evenly spaced or
 * listed values; several make the full grid, the last fastest), --sample (Philox4x32-10
 * random values of (seed, run) alone) or --from (a CSV table); the runs go to dyn_sweep_run
 * (dynkit/sweep.h) on OpenMP threads; the table is written in run order, CSV with the shortest
 * decimals that read back (dyn_format_double).
 * Ctrl-C writes the finished runs, and --resume FILE runs only the others. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <float.h>
#include <math.h>
#include <signal.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "cli.h"
#include "util/escape.h"
#include "dynkit/io.h"
#include "dynkit/sweep.h"
#include "util/out_file.h"
#include "commands/sweep_bands.h"
#include "tables/sweep_table.h"
#include "tables/table_formats.h"
#ifdef DYNKIT_HAVE_MPI
#include <mpi.h>

#include "dynkit/sweep_mpi.h"
#endif

#define SWEEP_MAX_VARS 32
#define SWEEP_MAX_REDUCE 64
#define SWEEP_MAX_ROWS 100000000L

static void sweep_help(void)
{
    puts("Usage: dynkit sweep MODEL [run options] (--vary ... | --sample ... | --from FILE)\n"
         "                    [--reduce LIST] [--threads N] [--output FILE] [--resume FILE]\n"
         "\n"
         "Runs MODEL many times with one method and one set of run options, each run with its\n"
         "own parameter or initial-state values, and writes one row per run, in run order:\n"
         "run,<varied names>,<reduced names>, a reduction named OP_NAME (max_height for\n"
         "max:height). Runs are numbered from 0. Numbers are the shortest decimals that read\n"
         "back to the same double; a failed run (a state NaN or Inf, the step size\n"
         "underflowing, --max-steps reached, parameters the model refuses) is a row of nan\n"
         "with its reason in a last column 'status' (present when a run failed: ok,\n"
         "nonfinite, step-size, max-steps, rhs, parameters, bound, zeno). The results are the\n"
         "same bytes for any number of threads.\n"
         "\n"
         "The runs (one of):\n"
         "  --vary NAME=A:B:N    N values from A to B, A + k (B-A)/(N-1), the ends exactly A\n"
         "                       and B; NAME a parameter or a state (its initial value)\n"
         "  --vary NAME=V1,V2,.. the values listed; several --vary make the full grid, the\n"
         "                       last --vary varying fastest (as the innermost loop)\n"
         "  --sample NAME=DIST   random values: uniform(A,B), normal(MEAN,SD), lognormal(M,S)\n"
         "                       (exp of normal(M,S)); repeatable, one column each\n"
         "  --runs N             the number of random runs (with --sample); alone, for a model\n"
         "                       with noise (wiener, normal, ran): N runs of its noise, run i\n"
         "                       with the noise of (S, i)\n"
         "  --seed S             the seed, a whole number 0..2^64-1 (default 1); run i's\n"
         "                       values depend on (S, i, column) alone: Philox4x32-10, normal\n"
         "                       values by the Box-Muller transform\n"
         "  --from FILE.csv      one run per row of a CSV table whose columns are named like\n"
         "                       parameters and states, or of a sweep's table (.csv, .json:\n"
         "                       its varied names)\n"
         "Numbers may be multiples of pi (pi/4) or degrees (45deg), as in --set.\n"
         "\n"
         "What each run gives (--reduce, comma-separated; default: final):\n"
         "  final                every state at the end of the run (columns final_NAME)\n"
         "  final:NAME           a state or an output (dynkit info MODEL) at the end\n"
         "  max:NAME, min:NAME   largest, smallest value over the samples\n"
         "  argmax:NAME, argmin:NAME   the time of the (first) largest, smallest sample\n"
         "  mean:NAME            time average over the samples: the trapezoidal rule divided by\n"
         "                       the span\n"
         "  event:NAME           the time of the first occurrence of the model's event NAME\n"
         "                       (nan when it does not occur)\n"
         "  count:NAME           the number of occurrences of event NAME\n"
         "The samples are every step of a fixed-step method, and the --step grid of an\n"
         "adaptive one (the model's step by default). --event NAME:stop ends each run at the\n"
         "event's first occurrence (the end of the run for final, max, ...).\n"
         "\n"
         "Sweep options:\n"
         "  --threads N          threads (default: all cores, or OMP_NUM_THREADS)\n"
         "  -o, --output FILE    write the table to FILE in the format of its extension: .csv,\n"
         "                       .json, .npy, .npz or .mat (default: standard output, CSV);\n"
         "                       .json, .npz and .mat carry the units; outside CSV the status\n"
         "                       is the library's number (0 ok, 3 nonfinite, 7 step-size,\n"
         "                       8 max-steps; docs/sweeps.md)\n"
         "  --resume FILE        keep the finished runs of FILE (a table an interrupted sweep\n"
         "                       with the same options wrote), run the others, and write the\n"
         "                       whole table to --output (default: FILE itself)\n"
         "  --bands FILE         also write, at each time of the --step grid, the mean and the\n"
         "                       5th, 50th and 95th percentiles of every state over the runs\n"
         "                       (t, mean_X, p5_X, p50_X, p95_X; format by the extension);\n"
         "                       'dynkit plot FILE' draws them as bands\n"
         "  --quiet              no progress bar (shown on a terminal only: runs, rate, ETA)\n"
         "Ctrl-C stops the sweep: the finished runs are written and the command to resume is\n"
         "printed (exit status 130). Failed runs do not change the exit status (0).\n"
         "Across processes: 'mpirun -n K dynkit sweep ...' splits the runs over K ranks (each\n"
         "on its own threads, --threads per rank) and rank 0 writes the one table, the same\n"
         "bytes as one process (when dynkit is built with MPI: libopenmpi-dev).\n"
         "\n"
         "The run options are those of dynkit run but --final, --every, --outputs, --times,\n"
         "--trace, --stats, --header and --events-output (each run is reduced to one row); in\n"
         "a sweep --output is the table's file.\n");
    cli_run_options_help(stdout);
    puts("\n"
         "Examples:\n"
         "  dynkit sweep pendulum --method dop853 --rtol 1e-12 --atol 1e-12 --tspan 0:5 "
         "--vary dphi=0.1:1.9:50 --reduce event:turn --event turn:stop\n"
         "  dynkit sweep vanderpol --method rk4 --step 0.01 --tspan 0:20 --vary mu=0.5,1,2,4 "
         "--reduce max:y1,argmax:y1,mean:y2\n"
         "  dynkit sweep pendulum --method rk4 --step 0.01 --tspan 0:10 --vary l=1:10:4 "
         "--vary dphi=0.5:1.5:3 --reduce max:height,count:bottom --output grid.csv\n"
         "  dynkit sweep vanderpol --method dp45 --tspan 0:10 --sample 'mu=uniform(0.5,2)' "
         "--sample 'y1=normal(2,0.1)' --runs 1000 --seed 7 --reduce final --output mc.csv\n"
         "  dynkit sweep vanderpol --method dp45 --tspan 0:10 --sample 'mu=uniform(0.5,2)' "
         "--sample 'y1=normal(2,0.1)' --runs 1000 --seed 7 --reduce final --resume mc.csv\n"
         "  dynkit sweep pendulum --method rk4 --step 0.01 --tspan 0:10 --from grid.csv "
         "--reduce final,max:energy --threads 2\n"
         "  dynkit sweep examples/models/ornstein_uhlenbeck.ode --runs 1000 --seed 2 "
         "--bands ou_bands.csv --output ou_runs.csv");
}

/* ---- the run table ---- */

typedef struct sweep_spec {
    int n_vars;
    dyn_sweep_var vars[SWEEP_MAX_VARS];
    /* --vary: the axes */
    double *axis[SWEEP_MAX_VARS];
    long count[SWEEP_MAX_VARS];
    /* --sample */
    dyn_dist dist[SWEEP_MAX_VARS];
    int n_vary, n_sample;
    const char *from;
    long runs;
    uint64_t seed;
    long n_runs;
    double *values; /* (n_runs x n_vars) */
} sweep_spec;

static void spec_free(sweep_spec *sp)
{
    for (int j = 0; j < SWEEP_MAX_VARS; j++)
        free(sp->axis[j]);
    free(sp->values);
}

static int add_var(const dyn_model *m, sweep_spec *sp, const char *name, size_t len,
                   const char *opt)
{
    char buf[128], err[1024];
    if (len == 0 || len >= sizeof buf)
        return cli_usage_error("sweep", "%s: give NAME=..., NAME a parameter or a state", opt);
    memcpy(buf, name, len);
    buf[len] = '\0';
    if (sp->n_vars >= SWEEP_MAX_VARS)
        return cli_usage_error("sweep", "at most %d varied names", SWEEP_MAX_VARS);
    dyn_sweep_var v;
    if (dyn_sweep_var_find(m, buf, &v, err, sizeof err))
        return cli_usage_error("sweep", "%s %s: %s", opt, buf, err);
    if (cli_param_is_size(m, buf))
        return cli_usage_error("sweep",
                               "%s %s: %s is the size of the model and cannot be swept; run "
                               "one sweep per size (%s:N)",
                               opt, buf, buf, m->name);
    for (int j = 0; j < sp->n_vars; j++)
        if (sp->vars[j].kind == v.kind && sp->vars[j].index == v.index)
            return cli_usage_error("sweep", "%s %s: %s is varied twice", opt, buf, buf);
    sp->vars[sp->n_vars++] = v;
    return CLI_OK;
}

/* --vary NAME=A:B:N or NAME=V1,V2,... */
static int parse_vary(const dyn_model *m, sweep_spec *sp, const char *text)
{
    const char *eq = strchr(text, '=');
    if (!eq)
        return cli_usage_error("sweep", "--vary '%s': give NAME=A:B:N or NAME=V1,V2,...", text);
    if (add_var(m, sp, text, (size_t)(eq - text), "--vary") != CLI_OK)
        return CLI_USAGE;
    const int j = sp->n_vars - 1;
    int rc = cli_parse_values("sweep", text, eq + 1, SWEEP_MAX_ROWS, &sp->axis[j], &sp->count[j]);
    if (rc != CLI_OK)
        return rc;
    sp->n_vary++;
    return CLI_OK;
}

/* --sample NAME=uniform(A,B)|normal(M,S)|lognormal(M,S) */
static int parse_sample(const dyn_model *m, sweep_spec *sp, const char *text)
{
    const char *eq = strchr(text, '=');
    if (!eq)
        return cli_usage_error("sweep",
                               "--sample '%s': give NAME=uniform(A,B), normal(MEAN,SD) or "
                               "lognormal(M,S)",
                               text);
    if (add_var(m, sp, text, (size_t)(eq - text), "--sample") != CLI_OK)
        return CLI_USAGE;
    static const struct {
        const char *name;
        dyn_dist_kind kind;
    } kinds[] = {{"uniform", DYN_DIST_UNIFORM},
                 {"normal", DYN_DIST_NORMAL},
                 {"lognormal", DYN_DIST_LOGNORMAL}};
    const char *v = eq + 1;
    const char *open = strchr(v, '('), *comma = open ? strchr(open, ',') : NULL;
    const char *close = comma ? strchr(comma, ')') : NULL;
    int kind = -1;
    for (size_t k = 0; open && k < sizeof kinds / sizeof kinds[0]; k++)
        if (strlen(kinds[k].name) == (size_t)(open - v) &&
            strncmp(v, kinds[k].name, (size_t)(open - v)) == 0)
            kind = (int)kinds[k].kind;
    char a_text[128], b_text[128];
    double a = 0, b = 0;
    int ok = kind >= 0 && close && close[1] == '\0' && (size_t)(comma - open) < sizeof a_text &&
             (size_t)(close - comma) < sizeof b_text;
    if (ok) {
        snprintf(a_text, sizeof a_text, "%.*s", (int)(comma - open - 1), open + 1);
        snprintf(b_text, sizeof b_text, "%.*s", (int)(close - comma - 1), comma + 1);
        ok = cli_parse_number(a_text, &a) == 0 && cli_parse_number(b_text, &b) == 0;
    }
    if (!ok)
        return cli_usage_error("sweep",
                               "--sample '%s': give NAME=uniform(A,B), normal(MEAN,SD) or "
                               "lognormal(M,S) with numbers A, B, ...",
                               text);
    if (kind == DYN_DIST_UNIFORM && !(b > a))
        return cli_usage_error("sweep", "--sample '%s': uniform(A,B) needs A < B", text);
    if (kind != DYN_DIST_UNIFORM && !(b >= 0))
        return cli_usage_error("sweep", "--sample '%s': the standard deviation must be >= 0",
                               text);
    /* every value the generator can give must be a finite number, or runs fail one by one:
     * u is in [2^-54, 1 - 2^-54] (dyn_dist_value), so |z| <= sqrt(-2 log 2^-54) = 8.65 */
    const double zmax = sqrt(-2.0 * log(ldexp(1.0, -54)));
    if (kind == DYN_DIST_UNIFORM && !isfinite(b - a))
        return cli_usage_error("sweep",
                               "--sample '%s': B - A is beyond the range of doubles, so the "
                               "values A + (B - A) u are not finite: give B - A below 1.8e308",
                               text);
    if (kind != DYN_DIST_UNIFORM && !(isfinite(a - b * zmax) && isfinite(a + b * zmax)))
        return cli_usage_error("sweep",
                               "--sample '%s': MEAN +- %.3g SD (the extremes of the normal "
                               "values drawn) must be finite numbers",
                               text, zmax);
    if (kind == DYN_DIST_LOGNORMAL && !isfinite(exp(a + b * zmax)))
        return cli_usage_error("sweep",
                               "--sample '%s': exp(M + %.3g S), the largest value drawn, is "
                               "beyond the range of doubles: give M + %.3g S <= %.6g",
                               text, zmax, zmax, log(DBL_MAX));
    sp->dist[sp->n_sample++] = (dyn_dist){(dyn_dist_kind)kind, a, b};
    return CLI_OK;
}

/* --from a sweep's table (CSV or JSON, sweep_table.h): its runs again, from the varied
 * names after the run column (up to the first column that is neither a parameter nor a
 * state: the reductions). */
static int read_from_sweep(const dyn_model *m, sweep_spec *sp, const sweep_table *st)
{
    int rc = CLI_OK, nv = 0;
    dyn_sweep_var v;
    char err[512];
    while (rc == CLI_OK && 1 + nv < st->cols && 1 + nv != st->status_col &&
           dyn_sweep_var_find(m, st->names[1 + nv], &v, err, sizeof err) == 0) {
        rc = add_var(m, sp, st->names[1 + nv], strlen(st->names[1 + nv]), "--from column");
        nv++;
    }
    if (rc == CLI_OK && nv == 0)
        rc = cli_usage_error("sweep", "--from %s: the column after run, %s, is neither a "
                                      "parameter nor a state of %s",
                             sp->from, st->cols > 1 ? st->names[1] : "(none)", m->name);
    if (rc != CLI_OK)
        return rc;
    sp->n_runs = st->rows;
    sp->values = malloc((size_t)st->rows * (size_t)nv * sizeof(double) + 1);
    if (!sp->values)
        return CLI_FAILED;
    for (long i = 0; i < st->rows; i++)
        for (int j = 0; j < nv; j++)
            sp->values[(size_t)i * (size_t)nv + (size_t)j] =
                st->data[(size_t)i * (size_t)st->cols + 1 + (size_t)j];
    return CLI_OK;
}

/* --from FILE.csv: every column a parameter or a state; or a sweep's table. */
static int read_from(const dyn_model *m, sweep_spec *sp)
{
    dyn_table t;
    char err[512];
    sweep_table st;
    cli_input_note(sp->from, "the --from table");
    if (sweep_table_read(sp->from, &st, err, sizeof err) == 0) {
        const int rc = read_from_sweep(m, sp, &st);
        sweep_table_free(&st);
        return rc;
    }
    sweep_table_free(&st);
    if (dyn_table_read_file(sp->from, 0, &t, err, sizeof err) != DYN_OK) {
        cli_error("--from: %s", err);
        return CLI_USAGE;
    }
    int rc = CLI_OK;
    for (int c = 0; c < t.cols && rc == CLI_OK; c++)
        rc = add_var(m, sp, t.names[c], strlen(t.names[c]), "--from column");
    if (rc == CLI_OK) {
        sp->n_runs = t.rows;
        sp->values = t.data;
        t.data = NULL;
    }
    dyn_table_free(&t);
    return rc;
}

static int build_table(sweep_spec *sp)
{
    if (sp->n_vary > 0) {
        const double *axes[SWEEP_MAX_VARS];
        for (int j = 0; j < sp->n_vars; j++)
            axes[j] = sp->axis[j];
        long rows = dyn_sweep_grid(sp->n_vars, axes, sp->count, NULL, SWEEP_MAX_ROWS);
        if (rows < 0)
            return cli_usage_error("sweep", "the grid of --vary has more than %ld runs",
                                   SWEEP_MAX_ROWS);
        sp->values = malloc((size_t)rows * (size_t)sp->n_vars * sizeof(double));
        if (!sp->values)
            return CLI_FAILED;
        sp->n_runs = dyn_sweep_grid(sp->n_vars, axes, sp->count, sp->values, SWEEP_MAX_ROWS);
    } else if (sp->n_sample > 0) {
        sp->n_runs = sp->runs;
        sp->values = malloc((size_t)sp->runs * (size_t)sp->n_vars * sizeof(double));
        if (!sp->values)
            return CLI_FAILED;
        dyn_sweep_sample(sp->dist, sp->n_vars, sp->seed, 0, sp->runs, sp->values);
    }
    return CLI_OK;
}

/* ---- statuses as words ---- */

static const struct {
    int status;
    const char *word;
} status_words[] = {{DYN_OK, "ok"},
                    {DYN_ERR_NONFINITE, "nonfinite"},
                    {DYN_ERR_STEP_SIZE, "step-size"},
                    {DYN_ERR_MAX_STEPS, "max-steps"},
                    {DYN_ERR_RHS, "rhs"},
                    {DYN_ERR_ARG, "parameters"},
                    {DYN_STOPPED, "bound"},
                    {DYN_ERR_ZENO, "zeno"},
                    {DYN_ERR_CAPACITY, "capacity"},
                    {DYN_ERR_IO, "io"}};

static const char *status_word(int st)
{
    for (size_t k = 0; k < sizeof status_words / sizeof status_words[0]; k++)
        if (status_words[k].status == st)
            return status_words[k].word;
    return "failed";
}

static int status_of_word(const char *w, int *st)
{
    for (size_t k = 0; k < sizeof status_words / sizeof status_words[0]; k++)
        if (strcmp(status_words[k].word, w) == 0) {
            *st = status_words[k].status;
            return 0;
        }
    return -1;
}

/* ---- the table ---- */

typedef struct sweep_out {
    const dyn_model *m;
    const sweep_spec *sp;
    const dyn_reduce *red;
    int n_red;
    double *results; /* (n_runs x n_red) */
    int *status;     /* (n_runs) */
} sweep_out;

static int put_number(FILE *f, double x)
{
    if (isnan(x))
        return fputs(",nan", f) < 0 ? -1 : 0;
    if (isinf(x))
        return fputs(x > 0 ? ",inf" : ",-inf", f) < 0 ? -1 : 0;
    char num[DYN_DOUBLE_CHARS + 1] = ",";
    const int len = 1 + dyn_format_double(x, num + 1);
    return fwrite(num, 1, (size_t)len, f) != (size_t)len ? -1 : 0;
}

/* The header; with colon, the reductions named OP:NAME as tables of earlier versions of
 * dynkit have them (read by --resume). */
static void header_line(const sweep_out *o, int with_status, int colon, char *buf, size_t size)
{
    size_t used = (size_t)snprintf(buf, size, "run");
    char name[160];
    for (int j = 0; j < o->sp->n_vars && used < size; j++)
        used += (size_t)snprintf(buf + used, size - used, ",%s",
                                 dyn_sweep_var_name(o->m, &o->sp->vars[j]));
    for (int r = 0; r < o->n_red && used < size; r++) {
        dyn_reduce_name(o->m, &o->red[r], name, sizeof name);
        if (colon)
            name[strcspn(name, "_")] = ':'; /* OP_NAME: the operations have no '_' */
        used += (size_t)snprintf(buf + used, size - used, ",%s", name);
    }
    if (with_status && used < size)
        snprintf(buf + used, size - used, ",status");
}

/* The finished runs in run order; returns 0 or -1 (a write failed). */
static int write_table(FILE *f, const sweep_out *o)
{
    int with_status = 0;
    for (long i = 0; i < o->sp->n_runs; i++)
        with_status |= o->status[i] != DYN_OK && o->status[i] != DYN_SWEEP_NOT_RUN;
    char head[8192];
    header_line(o, with_status, 0, head, sizeof head);
    int bad = fprintf(f, "%s\n", head) < 0;
    const int nv = o->sp->n_vars;
    for (long i = 0; i < o->sp->n_runs && !bad; i++) {
        if (o->status[i] == DYN_SWEEP_NOT_RUN)
            continue;
        bad |= fprintf(f, "%ld", i) < 0;
        for (int j = 0; j < nv; j++)
            bad |= put_number(f, o->sp->values[(size_t)i * (size_t)nv + (size_t)j]);
        for (int r = 0; r < o->n_red; r++)
            bad |= put_number(f, o->results[(size_t)i * (size_t)o->n_red + (size_t)r]);
        if (with_status)
            bad |= fprintf(f, ",%s", status_word(o->status[i])) < 0;
        bad |= fputc('\n', f) == EOF;
    }
    bad |= fflush(f) != 0 || ferror(f);
    return bad ? -1 : 0;
}

/* The table as JSON, NPY, NPZ or MAT (table_formats.h): columns run, the varied names, the
 * reductions, and when a run failed a numeric status (the library's dyn_status: 0 ok). */
static int write_data_file(FILE *f, cli_format format, const sweep_out *o, const cli_run *run)
{
    const dyn_model *m = o->m;
    const int nv = o->sp->n_vars, nr = o->n_red;
    int with_status = 0;
    for (long i = 0; i < o->sp->n_runs; i++)
        with_status |= o->status[i] != DYN_OK && o->status[i] != DYN_SWEEP_NOT_RUN;
    const int cols = 1 + nv + nr + with_status;
    const char **names = calloc((size_t)cols, sizeof *names);
    const char **units = calloc((size_t)cols, sizeof *units);
    char(*red_names)[160] = calloc((size_t)nr + 1, sizeof *red_names);
    double *row = calloc((size_t)cols, sizeof *row);
    if (!names || !units || !red_names || !row) {
        free(names);
        free(units);
        free(red_names);
        free(row);
        return -1;
    }
    names[0] = "run";
    units[0] = "1";
    for (int j = 0; j < nv; j++) {
        const dyn_sweep_var *v = &o->sp->vars[j];
        names[1 + j] = dyn_sweep_var_name(m, v);
        units[1 + j] = v->kind == DYN_SWEEP_PARAM ? m->params[v->index].unit
                                                  : m->states[v->index].unit;
    }
    for (int r = 0; r < nr; r++) {
        const dyn_reduce *rd = &o->red[r];
        names[1 + nv + r] = dyn_reduce_name(m, rd, red_names[r], sizeof red_names[r]);
        if (rd->op == DYN_REDUCE_EVENT || rd->op == DYN_REDUCE_ARGMAX ||
            rd->op == DYN_REDUCE_ARGMIN)
            units[1 + nv + r] = "s";
        else if (rd->op == DYN_REDUCE_COUNT)
            units[1 + nv + r] = "1";
        else
            units[1 + nv + r] = rd->source == DYN_SOURCE_STATE ? m->states[rd->index].unit
                                                               : m->outputs[rd->index].unit;
    }
    if (with_status) {
        names[cols - 1] = "status";
        units[cols - 1] = "1";
    }
    /* run->rtol and atol are the model's when not given (run_options.c) */
    const int adaptive = dyn_method_is_adaptive(run->method);
    cli_table_info info = {
        .model = m->name,
        .method = run->method->name,
        .step = run->step,
        .rtol = adaptive && !run->rtolv ? (run->rtol > 0 ? run->rtol : DYN_DEFAULT_RTOL) : NAN,
        .atol = adaptive && !run->atolv ? (run->atol > 0 ? run->atol : DYN_DEFAULT_ATOL) : NAN,
        .t0 = run->t0,
        .t1 = run->t1,
        .cols = cols,
        .n_y = m->n_states,
        .names = names,
        .units = units,
        .header = CLI_HEADER_NAMES,
        .sweep = 1,
        .n_varied = nv,
        .n_reduced = nr};
    char err[512] = "a write failed";
    cli_table *tab = cli_table_open(f, format, &info, err, sizeof err);
    int bad = tab == NULL;
    for (long i = 0; i < o->sp->n_runs && !bad; i++) {
        if (o->status[i] == DYN_SWEEP_NOT_RUN)
            continue;
        for (int j = 0; j < nv; j++)
            row[j] = o->sp->values[(size_t)i * (size_t)nv + (size_t)j];
        for (int r = 0; r < nr; r++)
            row[nv + r] = o->results[(size_t)i * (size_t)nr + (size_t)r];
        if (with_status)
            row[nv + nr] = o->status[i];
        bad |= cli_table_row(tab, (double)i, row, cols - 1, NULL, 0) != 0;
    }
    if (tab) {
        bad |= cli_table_finish(tab, err, sizeof err) != 0;
        cli_table_free(tab);
    }
    if (bad)
        cli_error("--output: %s", err);
    free(names);
    free(units);
    free(red_names);
    free(row);
    return bad ? -1 : 0;
}

/* --resume FILE: the finished runs of a table written by the same sweep. Marks them in
 * skip and fills their rows and statuses; returns CLI_OK or an error (printed). */
static int read_resume(const char *path, sweep_out *o, unsigned char *skip, long *kept)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        cli_error("--resume: cannot open %s: %s", path, strerror(errno));
        return CLI_USAGE;
    }
    size_t cap = 1 << 16;
    char *line = malloc(cap);
    char head[8192], head_status[8192], old[8192], old_status[8192];
    header_line(o, 0, 0, head, sizeof head);
    header_line(o, 1, 0, head_status, sizeof head_status);
    header_line(o, 0, 1, old, sizeof old);
    header_line(o, 1, 1, old_status, sizeof old_status);
    int rc = CLI_OK, with_status = 0;
    long lineno = 0;
    *kept = 0;
    const int nv = o->sp->n_vars;
    while (line && rc == CLI_OK && fgets(line, (int)cap, f)) {
        lineno++;
        size_t len = strlen(line);
        const int complete = len > 0 && line[len - 1] == '\n';
        while (len > 0 && (line[len - 1] == '\n' || line[len - 1] == '\r'))
            line[--len] = '\0';
        if (lineno == 1 && strncmp(line, "\xEF\xBB\xBF", 3) == 0) { /* a UTF-8 BOM */
            memmove(line, line + 3, len - 2);
            len -= 3;
        }
        if (!complete && lineno > 1 && len > 0 && feof(f)) {
            /* the last row cut mid-line, as a crash or a full disk leaves it: its run is
             * made again */
            cli_note("--resume: %s:%ld: the last row is cut off (no line "
                            "end); its run is made again",
                    path, lineno);
            break;
        }
        if (lineno == 1) {
            with_status = strcmp(line, head_status) == 0 || strcmp(line, old_status) == 0;
            if (!with_status && strcmp(line, head) != 0 && strcmp(line, old) != 0) {
                cli_error("--resume: %s is not a table of this sweep: its header is\n  %s\nand "
                          "this sweep writes\n  %s\n(give the same model, runs and --reduce as "
                          "the sweep that wrote it)",
                          path, line, head);
                rc = CLI_USAGE;
            }
            continue;
        }
        if (len == 0)
            continue;
        char *p = line, *end;
        errno = 0;
        long run = strtol(p, &end, 10);
        int ok = end != p && *end == ',' && run >= 0 && run < o->sp->n_runs && !skip[run];
        p = end;
        for (int j = 0; j < nv && ok; j++) {
            double x = strtod(p + 1, &end);
            ok = *p == ',' && end != p + 1 &&
                 x == o->sp->values[(size_t)run * (size_t)nv + (size_t)j];
            p = end;
        }
        double *row = ok ? o->results + (size_t)run * (size_t)o->n_red : NULL;
        for (int r = 0; r < o->n_red && ok; r++) {
            row[r] = strtod(p + 1, &end);
            ok = *p == ',' && end != p + 1;
            p = end;
        }
        int st = DYN_OK;
        if (ok && with_status)
            ok = *p == ',' && status_of_word(p + 1, &st) == 0;
        else if (ok)
            ok = *p == '\0';
        if (!ok) {
            cli_error("--resume: %s:%ld: not a row of this sweep (a run number 0..%ld not seen "
                      "before, the same values of the varied names, then %d numbers%s)",
                      path, lineno, o->sp->n_runs - 1, o->n_red,
                      with_status ? " and a status" : "");
            rc = CLI_USAGE;
            break;
        }
        o->status[run] = st;
        skip[run] = 1;
        (*kept)++;
    }
    if (!line)
        rc = CLI_FAILED;
    if (rc == CLI_OK && lineno == 0) {
        cli_error("--resume: %s is empty", path);
        rc = CLI_USAGE;
    }
    free(line);
    fclose(f);
    return rc;
}

/* --resume: the first finished run of the table, run again with this sweep's options, must
 * give its row and status bit for bit (a run depends only on its row of the run table: the
 * determinism of docs/sweeps.md); otherwise the table was made with other run options
 * (method, step, tspan, tolerances, --set, ...) that its header does not show, or by another
 * dynkit, and is refused rather than mixed with runs of these options. */
static int check_resumed(const dyn_sweep *s, const sweep_out *o, const unsigned char *skip,
                         const char *path)
{
    long probe = -1;
    for (long i = 0; i < s->n_runs && probe < 0; i++)
        if (skip[i])
            probe = i;
    if (probe < 0)
        return CLI_OK;
    const size_t n_red = (size_t)o->n_red;
    double *mine = malloc((n_red + 1) * sizeof *mine);
    if (!mine) {
        cli_error("out of memory");
        return CLI_FAILED;
    }
    /* a sweep of that one row of the run table */
    dyn_sweep one = *s;
    one.n_runs = 1;
    one.values = s->values + (size_t)probe * (size_t)s->n_vars;
    one.skip = NULL;
    one.threads = 1;
    one.progress = NULL;
    one.cancel = NULL;
    int status = DYN_SWEEP_NOT_RUN, rc = CLI_OK;
    char err[512];
    const int src = dyn_sweep_run(&one, mine, &status, err, sizeof err);
    if (src != DYN_OK) {
        cli_error("%s", err);
        rc = src == DYN_ERR_ARG ? CLI_USAGE : CLI_FAILED;
    }
    const double *kept = o->results + (size_t)probe * n_red;
    /* the first column that differs, or n_red for the status */
    size_t differs = status != o->status[probe] ? n_red : n_red + 1;
    for (size_t r = 0; r < n_red && differs > n_red; r++)
        if (!(isnan(mine[r]) && isnan(kept[r])) && memcmp(&mine[r], &kept[r], sizeof mine[r]) != 0)
            differs = r;
    if (rc == CLI_OK && differs <= n_red) {
        char name[160], got[64], had[64];
        if (differs < n_red) {
            dyn_reduce_name(o->m, &o->red[differs], name, sizeof name);
            snprintf(got, sizeof got, "%s", dyn_shortest(mine[differs]).s);
            snprintf(had, sizeof had, "%s", dyn_shortest(kept[differs]).s);
        } else {
            snprintf(name, sizeof name, "status");
            snprintf(got, sizeof got, "%s", status_word(status));
            snprintf(had, sizeof had, "%s", status_word(o->status[probe]));
        }
        cli_error("--resume: %s was made with other run options: its run %ld, run "
                "again with these, gives %s = %s where the file has %s.\nThe table does not "
                "record the method, step, tspan, tolerances or --set: give those of the sweep "
                "that wrote it (and the same dynkit)",
                path, probe, name, got, had);
        rc = CLI_USAGE;
    }
    free(mine);
    return rc;
}

/* ---- progress and Ctrl-C ---- */

static volatile sig_atomic_t sweep_signal;

static void on_signal(int sig)
{
    sweep_signal = sig;
    signal(sig, SIG_DFL); /* a second one ends the program */
}

/* Catch sig with sa, unless it was ignored when dynkit started (nohup, a background job of
 * a shell without job control): that stays ignored, as for the other commands. The handler
 * before into old, to be put back. */
static void catch_unless_ignored(int sig, const struct sigaction *sa, struct sigaction *old)
{
    sigaction(sig, NULL, old);
    if (old->sa_handler != SIG_IGN)
        sigaction(sig, sa, NULL);
}

static int sweep_cancelled(void *ctx)
{
    (void)ctx;
    return sweep_signal != 0;
}

static double now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef struct sweep_progress {
    int enabled, shown;
    double start, last;
    long kept;
} sweep_progress;

static int sweep_progress_update(long run, int status, long done, long total, void *ctx)
{
    sweep_progress *p = ctx;
    (void)run;
    (void)status;
    if (!p->enabled)
        return 0;
    const double t = now_seconds(), elapsed = t - p->start;
    if ((elapsed < 0.5 || t - p->last < 0.1) && done < total)
        return 0;
    if (!p->shown && done == total)
        return 0;
    p->last = t;
    const double rate = elapsed > 0 ? (double)done / elapsed : 0.0;
    const double eta = rate > 0 ? (double)(total - done) / rate : 0.0;
    char bar[31];
    const int fill = total > 0 ? (int)(30.0 * (double)done / (double)total) : 30;
    for (int k = 0; k < 30; k++)
        bar[k] = k < fill ? '#' : '.';
    bar[30] = '\0';
    fprintf(stderr, "\r  [%s] %5.1f%%  %ld/%ld runs  %.0f runs/s  ETA %.0f s ", bar,
            total > 0 ? 100.0 * (double)done / (double)total : 100.0, done + p->kept,
            total + p->kept, rate, eta);
    p->shown = 1;
    return 0;
}

/* ---- the command ---- */

/* Run options that do not apply to a sweep. */
static int refused_option(const char *arg)
{
    static const char *const refused[] = {"--final", "--every",  "--outputs",      "--times",
                                          "--trace", "--stats", "--header", "--events-output"};
    for (size_t k = 0; k < sizeof refused / sizeof refused[0]; k++) {
        size_t len = strlen(refused[k]);
        if (strncmp(arg, refused[k], len) == 0 && (arg[len] == '\0' || arg[len] == '='))
            return cli_usage_error("sweep",
                                   "%s does not apply to a sweep: each run is reduced to one "
                                   "row by --reduce (e.g. --reduce final,max:NAME)",
                                   refused[k]);
    }
    return CLI_OK;
}

static int sweep_command(int argc, char **argv, int rank, int ranks)
{
    (void)ranks;
    for (int i = 0; i < argc; i++)
        if (cli_is_help(argv[i])) {
            sweep_help();
            return CLI_OK;
        }
    if (argc < 1 || argv[0][0] == '-') {
        char names[512];
        return cli_usage_error("sweep", "missing MODEL (accepted: %s, or a model file)",
                               dyn_model_names(names, sizeof names));
    }
    /* the sweep's own options; the rest are run options */
    char **pass = calloc((size_t)argc + 1, sizeof *pass);
    const char **vary = calloc((size_t)argc + 1, sizeof *vary);
    const char **sample = calloc((size_t)argc + 1, sizeof *sample);
    if (!pass || !vary || !sample) {
        free(pass);
        free(vary);
        free(sample);
        return CLI_FAILED;
    }
    int n_pass = 0, n_vary_opt = 0, n_sample_opt = 0, rc = CLI_OK, init_given = 0;
    const char *reduce = "final", *threads_text = NULL, *output = NULL, *resume = NULL;
    const char *runs_text = NULL, *seed_text = NULL, *from = NULL, *bands = NULL;
    pass[n_pass++] = argv[0];
    for (int i = 1; i < argc && rc == CLI_OK; i++) {
        const char *v = NULL;
        int r;
#define SOPT(name, dest)                                                               \
    if ((r = cli_option(argc, argv, &i, name, &v)) != 0) {                             \
        if (r < 0)                                                                     \
            rc = cli_usage_error("sweep", "option --%s needs a value", name);          \
        else                                                                           \
            dest;                                                                      \
        continue;                                                                      \
    }
        SOPT("vary", vary[n_vary_opt++] = v)
        SOPT("sample", sample[n_sample_opt++] = v)
        SOPT("runs", runs_text = v)
        SOPT("seed", seed_text = v)
        SOPT("from", from = v)
        SOPT("reduce", reduce = v)
        SOPT("threads", threads_text = v)
        SOPT("output", output = v)
        SOPT("resume", resume = v)
        SOPT("bands", bands = v)
#undef SOPT
        rc = refused_option(argv[i]);
        init_given |= strncmp(argv[i], "--init", 6) == 0;
        pass[n_pass++] = argv[i];
    }
    cli_run run;
    memset(&run, 0, sizeof run);
    sweep_spec sp;
    memset(&sp, 0, sizeof sp);
    sp.seed = 1;
    if (rc == CLI_OK)
        rc = cli_run_parse("sweep", n_pass, pass, &run);
    const dyn_model *m = run.model;
    const int sources = (n_vary_opt > 0) + (n_sample_opt > 0) + (from != NULL);
    /* a model with noise: --runs N alone are N realisations of its noise */
    const int noise_runs = rc == CLI_OK && m->n_noise > 0 && sources == 0 && runs_text;
    if (rc == CLI_OK && sources != 1 && !noise_runs)
        rc = cli_usage_error("sweep", sources == 0
                                          ? "give the runs: --vary NAME=A:B:N, --sample "
                                            "NAME=uniform(A,B) --runs N, or --from FILE.csv"
                                          : "give the runs one way: --vary, --sample or --from "
                                            "(not together)");
    if (rc == CLI_OK && cli_method_is_cvode(run.method))
        rc = cli_usage_error("sweep", "sweeps run the library's methods; cvode is not one of "
                                      "them (use rodas4 for stiff models)");
    for (int k = 0; k < n_vary_opt && rc == CLI_OK; k++)
        rc = parse_vary(m, &sp, vary[k]);
    for (int k = 0; k < n_sample_opt && rc == CLI_OK; k++)
        rc = parse_sample(m, &sp, sample[k]);
    if (rc == CLI_OK && n_sample_opt > 0 && !runs_text)
        rc = cli_usage_error("sweep", "--sample needs --runs N (how many random runs)");
    if (rc == CLI_OK && (runs_text || seed_text) && n_sample_opt == 0 && m->n_noise == 0)
        rc = cli_usage_error("sweep", "--runs and --seed go with --sample (or with a model "
                                      "with noise: wiener, normal, ran)");
    if (rc == CLI_OK && runs_text && m->n_noise > 0 && n_sample_opt == 0 && sources > 0)
        rc = cli_usage_error("sweep", "--runs N with --vary or --from: each run of the table "
                                      "already has its own noise (stream = its run number)");
    if (rc == CLI_OK && bands && resume)
        rc = cli_usage_error("sweep", "--bands with --resume: the resumed runs' time series "
                                      "are not in the table; run the sweep again");
    if (rc == CLI_OK && bands && ranks > 1)
        rc = cli_usage_error("sweep", "--bands runs in one process (the ranks do not share "
                                      "the time series)");
    if (rc == CLI_OK && bands && dyn_method_is_adaptive(run.method) && cli_run_at_steps(&run))
        rc = cli_usage_error("sweep", "--bands needs the runs on one grid of times: give "
                                      "--step");
    if (rc == CLI_OK && runs_text &&
        (cli_parse_count(runs_text, 1, &sp.runs) || sp.runs > SWEEP_MAX_ROWS))
        rc = cli_usage_error("sweep", "--runs '%s': give a whole number from 1 to %ld",
                             runs_text, SWEEP_MAX_ROWS);
    if (rc == CLI_OK && seed_text) {
        char *end;
        errno = 0;
        unsigned long long s = strtoull(seed_text, &end, 10);
        if (end == seed_text || *end || errno || seed_text[0] == '-')
            rc = cli_usage_error("sweep", "--seed '%s': give a whole number 0..2^64-1",
                                 seed_text);
        sp.seed = (uint64_t)s;
    }
    long threads = 0;
    if (rc == CLI_OK && threads_text &&
        (cli_parse_count(threads_text, 1, &threads) || threads > 4096))
        rc = cli_usage_error("sweep", "--threads '%s': give a whole number from 1 to 4096",
                             threads_text);
    if (rc == CLI_OK && from) {
        sp.from = from;
        rc = read_from(m, &sp);
    }
    if (rc == CLI_OK && noise_runs)
        sp.n_runs = sp.runs;
    if (rc == CLI_OK)
        rc = build_table(&sp);
    dyn_reduce red[SWEEP_MAX_REDUCE];
    int n_red = 0;
    char err[1024];
    if (rc == CLI_OK && dyn_reduce_parse(m, reduce, red, SWEEP_MAX_REDUCE, &n_red, err, sizeof err))
        rc = cli_usage_error("sweep", "--reduce: %s", err);
    for (int r = 0; r < n_red && rc == CLI_OK; r++)
        if (red[r].source == DYN_SOURCE_OUTPUT && !m->compute_outputs)
            rc = cli_usage_error("sweep", "--reduce: %s has no outputs", m->name);
    const char *out_path = output ? output : resume;
    cli_format format = CLI_FORMAT_CSV;
    if (rc == CLI_OK && out_path) {
        char ferr[512];
        if (cli_format_of_path(out_path, &format, ferr, sizeof ferr))
            rc = cli_usage_error("sweep", "--output: %s", ferr);
        for (int j = 0; j < sp.n_vars && rc == CLI_OK; j++) {
            const char *name = dyn_sweep_var_name(m, &sp.vars[j]);
            if ((format == CLI_FORMAT_NPZ || format == CLI_FORMAT_MAT) &&
                cli_table_name_taken(name))
                rc = cli_usage_error("sweep",
                                     "--output '%s': the column %s would have the name of "
                                     "another variable of the .%s file; write .csv, .json or "
                                     ".npy",
                                     out_path, name, cli_format_name(format));
        }
    }
    if (rc == CLI_OK && resume && !output && format != CLI_FORMAT_CSV)
        rc = cli_usage_error("sweep", "--resume '%s': give the CSV table of the interrupted "
                                      "sweep",
                             resume);
    free(pass);
    free(vary);
    free(sample);
#ifdef DYNKIT_HAVE_MPI
    if (ranks > 0) { /* every rank parsed the same options: go on only if all could */
        int bad = rc != CLI_OK, any = 0;
        MPI_Allreduce(&bad, &any, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
        if (any && rc == CLI_OK)
            rc = CLI_FAILED;
    }
#endif
    if (rc != CLI_OK) {
        spec_free(&sp);
        cli_run_free(&run);
        return rc;
    }

    /* the sweep */
    int stop[64], n_stop = 0;
    for (int k = 0; k < run.n_events && n_stop < 64; k++)
        if (run.events[k].terminal)
            for (int e = 0; e < m->n_events; e++)
                if (strcmp(m->events[e].name, run.events[k].name) == 0)
                    stop[n_stop++] = e;
    const long n_runs = sp.n_runs;
    sweep_out o = {m, &sp, red, n_red, NULL, NULL};
    o.results = malloc(((size_t)n_runs * (size_t)n_red + 1) * sizeof *o.results);
    o.status = malloc(((size_t)n_runs + 1) * sizeof *o.status);
    unsigned char *skip = calloc((size_t)n_runs + 1, 1);
    if (!o.results || !o.status || !skip) {
        cli_error("out of memory for %ld runs", n_runs);
        rc = CLI_FAILED;
    }
    for (long i = 0; i < n_runs && rc == CLI_OK; i++)
        o.status[i] = DYN_SWEEP_NOT_RUN;
    long kept = 0;
    if (rc == CLI_OK && resume)
        rc = read_resume(resume, &o, skip, &kept);
#ifdef DYNKIT_HAVE_MPI
    if (ranks > 0) {
        int bad = rc != CLI_OK, any = 0;
        MPI_Allreduce(&bad, &any, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
        if (any && rc == CLI_OK)
            rc = CLI_FAILED;
    }
#endif
    dyn_sweep s = {0};
    s.model = m;
    s.par = run.par;
    s.y0 = m->initial_state && !init_given ? NULL : run.y0;
    s.n_vars = sp.n_vars;
    s.vars = sp.vars;
    s.n_runs = n_runs;
    s.values = sp.values;
    s.method = run.method;
    s.t0 = run.t0;
    s.t1 = run.t1;
    s.step = dyn_method_is_adaptive(run.method) && cli_run_at_steps(&run) ? 0.0 : run.step;
    s.end = run.end;
    s.rtol = run.rtol;
    s.atol = run.atol;
    s.rtolv = run.rtolv;
    s.atolv = run.atolv;
    s.initial_step = run.initial_step;
    s.max_step = run.max_step;
    s.max_steps = run.max_steps;
    s.n_reduce = n_red;
    s.reduce = red;
    s.n_stop = n_stop;
    s.stop = stop;
    s.skip = skip;
    s.threads = (int)threads;
    s.seed = sp.seed;
    /* the matrices of a stiff method, those of dynkit run (cli_linear_choose): the band with
     * LAPACK's LU when built with it, else sparse matrices with KLU, one solver a thread */
    s.band_solver = cli_band_solver();
    if (dyn_method_is_stiff(run.method)) {
        cli_linear lin;
        cli_linear_choose(m, &lin);
        if (lin.kind == CLI_LINEAR_SPARSE) {
            s.sparse_open = cli_sparse_solver_open;
            s.sparse_close = cli_sparse_solver_close;
        }
    }
    s.noise_method = cli_sde_method(run.method);
    sweep_bands bd = {0};
    if (rc == CLI_OK && bands && (rc = sweep_bands_plan(&run, n_runs, &bd)) == CLI_OK) {
        s.series = bd.series;
        s.n_series = bd.n_times;
        s.series_every = bd.every;
    }
    if (rc == CLI_OK && kept > 0)
        rc = check_resumed(&s, &o, skip, resume);
    sweep_progress prog = {0};
    prog.enabled = !run.quiet && isatty(fileno(stderr));
    prog.start = prog.last = now_seconds();
    prog.kept = kept;
    s.progress = sweep_progress_update;
    s.progress_ctx = &prog;
    s.cancel = sweep_cancelled;
    struct sigaction sa, old_int, old_term;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sweep_signal = 0;
    int src = DYN_OK;
    if (rc == CLI_OK) {
        catch_unless_ignored(SIGINT, &sa, &old_int);
        catch_unless_ignored(SIGTERM, &sa, &old_term);
#ifdef DYNKIT_HAVE_MPI
        if (ranks > 0)
            src = dyn_sweep_mpi_run(&s, o.results, o.status, err, sizeof err);
        else
#endif
            src = dyn_sweep_run(&s, o.results, o.status, err, sizeof err);
        sigaction(SIGINT, &old_int, NULL);
        sigaction(SIGTERM, &old_term, NULL);
        if (prog.shown)
            fputs("\r\033[K", stderr);
        if (src != DYN_OK && src != DYN_CANCELLED) {
            cli_error("%s", err);
            rc = src == DYN_ERR_ARG ? CLI_USAGE : CLI_FAILED;
        }
    }

    /* the table: rank 0 writes it */
    if (rc == CLI_OK && rank != 0) {
        free(o.results);
        free(o.status);
        free(skip);
        spec_free(&sp);
        cli_run_free(&run);
        return src == DYN_CANCELLED ? 128 + (int)sweep_signal : CLI_OK;
    }
    if (rc == CLI_OK) {
        /* a file is written beside its name and renamed when complete (out_file.h) */
        cli_out outf;
        if (bands)
            rc = sweep_bands_write(bands, &bd, &run, o.status, n_runs);
        if (rc != CLI_OK) {
        } else if ((rc = cli_out_open(&outf, "--output", out_path)) != CLI_OK) {
        } else {
            const int bad = format == CLI_FORMAT_CSV
                                ? write_table(outf.f, &o)
                                : write_data_file(outf.f, format, &o, &run);
            /* a failed write is reported by cli_out_close, or at exit for stdout */
            const int close_rc = cli_out_close(&outf, !bad);
            rc = close_rc != CLI_OK ? close_rc : bad ? CLI_FAILED : CLI_OK;
        }
    }
    if (rc == CLI_OK) {
        long done = 0, failed = 0;
        for (long i = 0; i < n_runs; i++) {
            done += o.status[i] != DYN_SWEEP_NOT_RUN;
            failed += o.status[i] != DYN_SWEEP_NOT_RUN && o.status[i] != DYN_OK;
        }
        if (failed > 0)
            cli_stderr("dynkit: %ld of %ld runs failed (see the status column)\n", failed, done);
        for (int r = 0; r < n_red; r++) {
            if (red[r].op != DYN_REDUCE_EVENT)
                continue;
            int seen = 0;
            for (long i = 0; i < n_runs && !seen; i++)
                seen = o.status[i] == DYN_OK && !isnan(o.results[(size_t)i * (size_t)n_red + (size_t)r]);
            if (!seen && done > failed)
                cli_note("event %s occurred in no run within %g:%g s (a longer "
                        "--tspan?)",
                        m->events[red[r].index].name, run.t0, run.t1);
        }
        if (src == DYN_CANCELLED) {
            char shown[4 * 4096 + 1];
            const char *named = out_path ? cli_terminal_text(out_path, 0, shown, sizeof shown)
                                         : "standard output";
            cli_stderr("dynkit: interrupted: %ld of %ld runs done, written to %s.\n"
                       "dynkit: to run the others, give the same command with --resume %s\n",
                       done, n_runs, named,
                       out_path && strcmp(out_path, "-") != 0 ? named
                                                              : "FILE (the table saved to FILE)");
            rc = 128 + (int)sweep_signal;
        }
    }
    free(o.results);
    free(o.status);
    free(skip);
    sweep_bands_free(&bd);
    spec_free(&sp);
    cli_run_free(&run);
    return rc;
}

/* The ranks of the MPI job this process belongs to (mpirun's environment), or 0 when it
 * was not started by mpirun. */
static int mpi_job_size(void)
{
    const char *vars[] = {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"};
    for (size_t k = 0; k < sizeof vars / sizeof vars[0]; k++) {
        const char *v = getenv(vars[k]);
        if (v && atoi(v) > 0)
            return atoi(v);
    }
    return 0;
}

int cli_cmd_sweep(int argc, char **argv)
{
    const int job = mpi_job_size();
#ifdef DYNKIT_HAVE_MPI
    if (job > 0) {
        int provided = 0, rank = 0, size = 1;
        if (MPI_Init_thread(NULL, NULL, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) {
            cli_error("MPI_Init_thread failed");
            return CLI_FAILED;
        }
        MPI_Comm_rank(MPI_COMM_WORLD, &rank);
        MPI_Comm_size(MPI_COMM_WORLD, &size);
        /* rank 0 speaks for the job: the others' messages would repeat its own */
        if (rank != 0) {
            FILE *o = freopen("/dev/null", "w", stdout), *e = freopen("/dev/null", "w", stderr);
            (void)o;
            (void)e;
        }
        const int rc = sweep_command(argc, argv, rank, size);
        MPI_Finalize();
        return rc;
    }
#else
    if (job > 1)
        return cli_usage_error("sweep",
                               "started by mpirun with %d processes, but dynkit was built "
                               "without MPI: each would run the whole sweep (install "
                               "libopenmpi-dev and rebuild, or run one process)",
                               job);
#endif
    return sweep_command(argc, argv, 0, 0);
}
