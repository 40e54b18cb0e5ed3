/* SPDX-License-Identifier: BSD-3-Clause */
/* Shared declarations of the dynkit command-line tool (the only part that prints/exits). */
#ifndef DYNKIT_CLI_H
#define DYNKIT_CLI_H

#include <stdio.h>

#include "dynkit/dynkit.h"
#include "dynkit/io.h"

/* v as the shortest decimal that reads back to it (dyn_format_double), in a buffer that lives
 * until the end of the enclosing block: fprintf(f, "t = %s", CLI_NUM(t)). */
#define CLI_NUM(v) cli_num((v), (char[DYN_DOUBLE_CHARS]){0})
static inline const char *cli_num(double v, char *buf)
{
    dyn_format_double(v, buf);
    return buf;
}

/* 1 when path names standard output under another name (/dev/stdout, /dev/fd/1,
 * /proc/self/fd/1): written as "-" is, to the stream the shell gave (out_file.c). */
int cli_is_stdout_name(const char *path);
/* 1 for "-.EXT" ("-.json", "-.npy"): standard output in the format of extension EXT (a file
 * of that name is written "./-.json"). cli_is_stdout_name is 1 for it too. */
int cli_is_stdout_format(const char *path);

/* Exit statuses of the contract. */
enum { CLI_OK = 0, CLI_FAILED = 1, CLI_USAGE = 2 };

/* Print "dynkit: error: <msg>" and a hint to the subcommand's --help; return CLI_USAGE.
 * Control bytes of the message (from names and lines of files) are escaped \xNN
 * (escape.h, cli_terminal_text); its line feeds are kept. */
int cli_usage_error(const char *command, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* Print "dynkit: error: <msg>" and a line feed, control bytes escaped as above. */
void cli_error(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;
/* "dynkit: warning: <msg>" and "dynkit: note: <msg>", escaped as cli_error's. */
void cli_warning(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;
void cli_note(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;
/* The message on stderr as it is formatted (no prefix, no line feed added), escaped as
 * cli_error's: for the lines of the tool's reports that quote names, messages or lines of
 * files (a run's events, its failure, its last good state). */
void cli_stderr(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;

/* Parse a finite number: decimal, optionally times pi ("pi/2", "-0.5pi", "2*pi/3") or an
 * angle in degrees ("45deg", converted to rad).
 * Returns 0 and *out, or -1 when text is not such a number. */
int cli_parse_number(const char *text, double *out);
/* A value of the command line (formula.c): a number as cli_parse_number reads it, else a
 * formula of the parameters of the model given to cli_formula_params (their values in par
 * when the formula is read), as a model file's `init` line takes it: 200-W*cos(0.3).
 * Returns 0 and *out, or -1 with why it is neither (into why, size bytes). */
int cli_parse_value(const char *text, double *out, char *why, size_t size);
void cli_formula_params(const dyn_model *m, const void *par);
/* Parse a count >= min (decimal or 1e6 style); 0 on success, -1 otherwise. */
int cli_parse_count(const char *text, long min, long *out);

/* The values of --vary NAME=VALUES (value_list.c): VALUES (v) "A:B:N", N evenly spaced
 * values from A to B (dyn_linspace_at), or "V1,V2,...", at most max of them, into *values
 * (owned, malloc) and *count. text is the whole option value, for messages. Returns CLI_OK,
 * or CLI_USAGE (message printed) or CLI_FAILED (out of memory). */
int cli_parse_values(const char *command, const char *text, const char *v, long max,
                     double **values, long *count);
/* Option matching: if argv[*i] is "--name" or "--name=VALUE", set *value (taking the next
 * argument when needed) and return 1; return -1 when the value is missing; 0 otherwise. */
int cli_option(int argc, char **argv, int *i, const char *name, const char **value);
/* Flag matching: 1 if argv[i] is exactly "--name". */
int cli_flag(const char *arg, const char *name);
/* The usage error for an unknown option arg of command, naming the nearest of options[0..n)
 * ("--name") when arg looks like a misspelling of it. Returns CLI_USAGE. */
int cli_unknown_option(const char *command, const char *arg, const char *const *options, int n);
/* 1 if arg is -h or --help. */
int cli_is_help(const char *arg);

/* The model MODEL names (model_open.c): a built-in name, or a model file. Returns CLI_OK
 * with *model, or a usage error (message printed, with the nearest known name). */
int cli_model_open(const char *command, const char *spec, const dyn_model **model);
/* For the mechanism files read next: on, their constraints need not hold at the file's
 * initial state (the run projects it, --project-init); lines (NULL: none) are read after
 * each file's own (dynkit inverse --prescribe). */
void cli_model_set_unchecked(int on);
/* The compiler options for a mechanism's generated C of source_len bytes: libtcc above 64 KiB
 * unless DYNKIT_JIT names a backend (model_open.c), else NULL (the default choice). */
struct dyn_jit_opts;
const struct dyn_jit_opts *cli_mech_jit_opts(size_t source_len);
void cli_model_set_mech_extra(const char *lines);
/* The options --table NAME=FILE among argv[1..argc) (the command's other options are left
 * to it), for the model file that cli_model_open opens next: its `table NAME FILE` is read
 * from FILE (dynkit/lang.h, dyn_ode_to_c_tables). CLI_OK or a usage error (printed). */
int cli_model_table_options(const char *command, int argc, char **argv);
/* 1 if MODEL names a model file (.ode, .c, .so) rather than a built-in model. */
int cli_model_is_file(const char *spec);
/* A model file's text (malloc'd, NUL-terminated, *len bytes); NULL with a message printed. */
char *cli_read_model_file(const char *path, size_t *len);
/* 1 for a model loaded from a model file with algebraic equations (0=...). */
int cli_model_has_algebraic(const dyn_model *m);
/* The C a model file (.ode, .mech) was translated to, as compiled; NULL for other models. */
const char *cli_model_c_source(const dyn_model *m);
/* The mechanism file's C as it was loaded (its tables, flags and extra lines) with the
 * outputs of its scene's inputs after the model's (DYN_MECH_SCENE_INPUTS): malloc'd, or NULL
 * (not a .mech file, or it cannot be read again). */
char *cli_model_mech_scene_source(const char *path);
/* The .ode file's C as it was loaded (its tables) with the numbers of the animation
 * ani_path's frames as outputs after the model's (dyn_ani_ode_to_c), or a .mech file's with
 * its scene's inputs, then those numbers (dyn_mech_ani_to_c): malloc'd, or NULL (neither, or
 * either file cannot be read or translated so). */
char *cli_model_ani_source(const char *ode_path, const char *ani_path);
/* The file m was defined in (dyn_model.source, else the file cli_model_open loaded it
 * from, e.g. a C model that names no source), or NULL for a built-in model. */
const char *cli_model_path(const dyn_model *m);
/* 1 when parameter `name` of m is its size (the Brusselator's N), which --set and sweeps
 * must not change: the size is chosen with the model (brusselator:N). */
int cli_param_is_size(const dyn_model *m, const char *name);
/* The band solver of stiff runs (band_solver.c): LAPACK's when built with it, else NULL
 * (the library's own). */
const dyn_band_solver *cli_band_solver(void);
/* The matrices of a stiff run of model m (band_solver.c): the library's choice
 * (dyn_run_linear_choose) with the backends the tool is built with: dense, band (the model's
 * band, declared or found in its exact pattern) or sparse (a pattern that is not banded,
 * with KLU), and why in words. */
typedef dyn_linear_choice cli_linear;
#define CLI_LINEAR_DENSE DYN_LINEAR_DENSE
#define CLI_LINEAR_BAND DYN_LINEAR_BAND
#define CLI_LINEAR_SPARSE DYN_LINEAR_SPARSE
/* The optional parts of the tool's runs (dyn_run): LAPACK's band LU, KLU, CVODE, as built. */
const dyn_run_backends *cli_run_backends(void);
void cli_linear_choose(const dyn_model *m, cli_linear *lin);
/* The sparse LU of stiff runs: KLU's (0), or none (1: built without it). Close releases it. */
int cli_sparse_solver_open(dyn_sparse_solver *s);
void cli_sparse_solver_close(dyn_sparse_solver *s);
/* The eigenvalue solver of linearize (band_solver.c): LAPACK's dgeev when built with it,
 * else NULL (the core has none). */
const struct dyn_eig_solver *cli_eig_solver(void);
/* --verbose (any command): notes on stderr, e.g. a model file's ignored options. */
void cli_set_verbose(int on);
int cli_verbose(void);

/* A model's default method and tolerances (model_defaults.c): its own, or DYN_MODEL_METHOD,
 * DYN_MODEL_RTOL, DYN_MODEL_ATOL when it names none; and where each comes from, in words
 * ("the model's", "@ rtol in ml.ode", "dynkit's default ..."), in buf or a constant. */
typedef enum { CLI_DEFAULT_METHOD, CLI_DEFAULT_RTOL, CLI_DEFAULT_ATOL } cli_default_field;
const char *cli_model_method(const dyn_model *m);
/* The unit of the model's time: dyn_model.time_unit, else "s" (model_defaults.c). */
const char *cli_time_unit(const dyn_model *m);
double cli_model_rtol(const dyn_model *m);
double cli_model_atol(const dyn_model *m);
const char *cli_model_default_source(const dyn_model *m, cli_default_field field, char *buf,
                                     size_t size);

/* Everything needed to make one run of a model: parsed from the run options. */
typedef struct cli_run {
    const dyn_model *model;
    const dyn_tableau *method;
    void *par;            /* model->par_size bytes (owned) */
    double *y0;           /* model->n_states (owned) */
    double t0, t1, step;
    dyn_end_policy end;
    const char *output_path; /* NULL = stdout */
    int header;           /* --header: cli_header (table_formats.h), CSV only */
    int final_only;
    int with_outputs;
    int quiet;
    int project_init;     /* --project-init: a mechanism's state moved onto its constraints */
    long every;
    long trace_steps;
    /* --forces FILE: a time table of the model's inputs, columns t and dyn_model.inputs */
    const char *forces_path;
    dyn_interp interp;    /* --interp hold|linear */
    double *input;        /* (input_rows x (1 + n_inputs)), owned; attached to par */
    long input_rows;
    /* adaptive methods (dyn_solve): tolerances, output times, step limits */
    double rtol, atol;    /* the model's (cli_model_rtol) unless --rtol/--atol */
    double *rtolv, *atolv; /* (n_states) per-state tolerances, owned, or NULL */
    double *times;        /* --times: (n_times) output times, owned, or NULL */
    long n_times;
    double max_step, initial_step; /* 0: automatic */
    long max_steps;       /* 0: no limit */
    int step_given;       /* --step was given (else step is the model's or the table's) */
    int stats;            /* --stats: counts on stderr */
    /* --event NAME[:stop]: the model's events to locate (copies, terminal as asked) */
    dyn_event *events;    /* (n_events), owned */
    int n_events;
    const char *events_path; /* --events-output FILE, or NULL */
    /* models with noise (dynkit/sde.h): --seed, and the run's stream (a sweep's run) */
    uint64_t seed, stream;
    /* --jac-pattern model|probe|none (NULL: model); for probe and none the run's model is
     * own_model, a copy with the pattern probed (owned with it) or none */
    const char *jac_pattern;
    dyn_model *own_model;
    dyn_sparse_pattern probed;
    /* a Poincaré map (run_section.c): --section, else the model's @ poimap (kind
     * DYN_POINCARE_NONE: none); section_var the state, n_states + the output, or -1 for t */
    dyn_poincare section;
    int section_var;
    int section_given;    /* --section was given (none included) */
    char *section_name;   /* owned copy of --section's variable */
} cli_run;

/* The event of run's section into ev (run_section.c): 1, 0 when the run has none, -1 out of
 * memory. Its g reads the run (one section at a time per process). */
int cli_section_event(const cli_run *run, dyn_event *ev);
/* The time a crossing at t is written with: k*T for a section in t (as XPPAUT), else t. */
double cli_section_time(const cli_run *run, double t);

/* The same for a run's method: cvode takes sparse matrices only with the model's exact
 * sparse values and SUNDIALS' KLU (else dense, saying why). */
void cli_linear_for_run(const cli_run *run, cli_linear *lin);
/* --jac-pattern of run (run_pattern.c): the model's pattern, a probed one, or none. */
int cli_run_jac_pattern(const char *command, cli_run *run);

/* Parse "MODEL [options]" of run-like commands into run; unknown options are errors.
 * Returns CLI_OK or CLI_USAGE (message printed). Free with cli_run_free. */
int cli_run_parse(const char *command, int argc, char **argv, cli_run *run);
/* The same for commands that make more runs (animate, plot): other_adaptive says that one
 * of the other runs (--compare) has an adaptive method, so that the tolerances and step
 * limits are accepted with a fixed-step main method. */
int cli_run_parse_with(const char *command, int argc, char **argv, int other_adaptive,
                       cli_run *run);

/* Samples of an adaptive run without --times: on the grid t0 + k*step, or at every accepted
 * step when the step is the model's default (no --step) and either the model asks for it
 * (dyn_model.samples) or its grid would have more than CLI_MAX_GRID_SAMPLES samples (a long
 * span such as Robertson's 0:1e11). */
#define CLI_MAX_GRID_SAMPLES 1000000L
int cli_run_at_steps(const cli_run *run);


/* ---- methods of the tool (methods.c): the library's registry plus, when dynkit is built
 * with SUNDIALS, "cvode" (the CVODE backend, not in the core registry) ---- */
/* The cvode descriptor (name, title; adaptive and stiff) or NULL when not built. */
const dyn_tableau *cli_cvode_method(void);
int cli_method_is_cvode(const dyn_tableau *m);
/* rkmil, the adaptive method for models with noise (dyn_sde_solve; not in the core
 * registry of deterministic methods): its descriptor, and whether m is it. */
const dyn_tableau *cli_rkmil_method(void);
int cli_method_is_rkmil(const dyn_tableau *m);
/* volterra, the method for models with Volterra integrals (dyn_volterra_solve), likewise */
int cli_method_is_volterra(const dyn_tableau *m);
/* sriw1, Rößler's strong order 1.5 method for models with noise (dyn_sde_solve), and whether
 * m is rkmil or sriw1: an adaptive method for noise. */
const dyn_tableau *cli_sriw1_method(void);
int cli_method_is_sde_adaptive(const dyn_tableau *m);
/* The dyn_sde_method that runs m on a model with noise: rkmil, sriw1, a map's, else
 * Euler–Maruyama. */
int cli_sde_method(const dyn_tableau *m);
/* Method by name or alias, cvode included when built; NULL if not available. */
const dyn_tableau *cli_method_find(const char *name);
/* Accepted method names, comma-separated, into buf; returns buf. */
char *cli_method_names(char *buf, size_t size);
/* The usage error for a method name cli_method_find refused: built without SUNDIALS
 * (cvode), or unknown with the accepted names. what names the option, e.g. "--method".
 * Returns CLI_USAGE. */
int cli_method_error(const char *command, const char *what, const char *name);
void cli_run_free(cli_run *run);
/* Help text of the run options (shared by run-like commands). */
void cli_run_options_help(FILE *out);
/* The same for the commands that draw (animate, plot): the run options without the data
 * file's (--output, --header, --final, --outputs, --trace, --stats, --events-output). */
void cli_view_options_help(FILE *out);

/* Run the parsed run: dyn_fixed_solve for a fixed-step method without events (the
 * homework's loop, exactly), dyn_cvode_solve for cvode (output times from the grid or
 * --times, or every step: cli_run_at_steps), dyn_solve otherwise (adaptive methods:
 * samples on the --step grid, at --times by dense output, or at every step; events). The
 * model's events that reset the state always take part (dyn_solve; the samples of a
 * fixed-step run stay on its grid); on_event sees only run->events. Samples go to output (k, t, y), events to
 * on_event (may be NULL), stages of the first run->trace_steps steps to the trace printer.
 * every > 1 lets the fixed-step driver hand over only every K-th sample and the last (the
 * general driver hands over all). y (n_states) receives the final state (the last good one
 * on failure). Returns the library's status (res filled), or DYN_ERR_ARG with res->message
 * for bad options, or -1 when out of memory. */
int cli_run_solve(const cli_run *run, long every, dyn_output_fn output, void *output_ctx,
                  dyn_event_fn on_event, void *event_ctx, dyn_progress_fn progress,
                  void *progress_ctx, double *y, dyn_result *res);
/* Number of the model's events that reset the state (0: none). */
int cli_run_resets(const cli_run *run);
/* The counts of a solve as one line: "steps=N accepted=N rejected=N rhs=N" (+ " jac=N"
 * for stiff methods, cvode included), without a newline, into buf; returns buf. */
char *cli_stats_line(const cli_run *run, const dyn_result *res, char *buf, size_t size);

/* Stage-by-stage trace printer for dyn_fixed_opts.trace; ctx is the cli_run. */
void cli_print_trace(const dyn_trace_stage *st, void *ctx);

/* Progress on stderr for long runs (only when stderr is a terminal). */
typedef struct cli_progress {
    int enabled;
    double start;     /* monotonic seconds */
    int shown;
    double last;      /* when the last line was shown */
} cli_progress;
void cli_progress_start(cli_progress *p, int quiet);
int cli_progress_update(double t, double fraction, void *ctx);
void cli_progress_finish(cli_progress *p);
/* The line `text` with the time elapsed, after the first second, at most ten times a
 * second (computations whose progress is not a fraction of a span). */
void cli_progress_text(cli_progress *p, const char *text);

/* Subcommands. */
int cli_cmd_run(int argc, char **argv);
int cli_cmd_models(int argc, char **argv);
int cli_cmd_methods(int argc, char **argv);
int cli_cmd_info(int argc, char **argv);
int cli_cmd_inverse(int argc, char **argv);
int cli_cmd_report(int argc, char **argv);
int cli_cmd_verify(int argc, char **argv);
int cli_cmd_sweep(int argc, char **argv);
int cli_cmd_linearize(int argc, char **argv);
int cli_cmd_continue(int argc, char **argv);
int cli_cmd_derive(int argc, char **argv);
int cli_cmd_equilibria(int argc, char **argv);
int cli_cmd_lyapunov(int argc, char **argv);
int cli_cmd_steady(int argc, char **argv);
int cli_cmd_bvp(int argc, char **argv);
/* dynkit plot TABLE.csv: a sweep's table as lines or a heat map (sweep_plot.c). */
int cli_plot_sweep_table(int argc, char **argv);

#endif
