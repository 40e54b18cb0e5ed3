/* SPDX-License-Identifier: BSD-3-Clause */
/* The run options shared by run-like commands: model, method, span, step, parameters,
 * initial state and output choices (the command-line contract of the design): the help
 * text, the option loop and the checks across options. Option values are parsed in
 * run_values.c, --forces tables read in run_input.c. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "dynkit/lang.h"
#include "run/mech_init.h"
#include "util/out_file.h"
#include "run/run_parse.h"
#include "tables/table_formats.h"

/* The run options every run-like command takes (up to --event). */
static void run_options_common(FILE *out)
{
    fputs("Run options:\n"
          "  -m, --method NAME    integration method (default: the model's; see 'dynkit methods';\n"
          "                       MATLAB's names too: ode45, ode23, ode15s, ode23s)\n"
          "  --step H             step size in s (default: the model's)\n"
          "  --tspan T0:T1        time span in s (default: the model's)\n"
          "  --end exact|grid     span not a whole number of steps: 'exact' (default) adds a\n"
          "                       shorter last step ending at T1; 'grid' stops at the last\n"
          "                       T0 + k*H <= T1 like MATLAB's T0:H:T1\n"
          "  --set NAME=VALUE     set a parameter (repeatable; see 'dynkit info MODEL')\n"
          "  --init NAME=VALUE    set an initial state (repeatable); numbers may be\n"
          "                       multiples of pi: pi/2, -0.5pi, 2*pi/3, or angles in\n"
          "                       degrees: 45deg (in rad)\n"
          "  --project-init       mechanism files: move the initial state onto the\n"
          "                       constraints (least change) and print what changed;\n"
          "                       without it a state that violates one is refused\n"
          "  --table NAME=FILE    a model file's 'table NAME FILE' read from FILE instead\n"
          "                       (repeatable; without it the table's file must be a regular\n"
          "                       file beside the model file, named without a folder)\n"
          "  --forces FILE        models with inputs (cart): read the inputs from a CSV table\n"
          "                       with columns t and the input names (cart: t,Fx,Fy), time\n"
          "                       increasing; without --step/--tspan the run uses the table's\n"
          "                       sample time and span ('dynkit inverse cart' writes one)\n"
          "  --interp hold|linear read the table between samples: 'hold' (default) takes the\n"
          "                       nearest sample, 'linear' interpolates; end values are held\n"
          "Adaptive methods (bs23 = ode23, dp45 = ode45, dop853; stiff: rodas4, and cvode\n"
          "when dynkit is built with SUNDIALS; see 'dynkit methods'):\n"
          "  --rtol R             relative tolerance (default: the model's, 'dynkit info MODEL',\n"
          "                       else 1e-6, and 1e-3 for a model with noise; below 100 eps\n"
          "                       it is raised to 100 eps with a warning)\n"
          "  --atol A             absolute tolerance (default: the model's, else 1e-9, and\n"
          "                       1e-6 for a model with noise); both\n"
          "                       accept one value per state, comma-separated, e.g.\n"
          "                       --atol 1e-8,1e-6\n"
          "                       each step keeps the error estimate below atol + rtol |y|\n"
          "                       --step H (above) writes samples at T0 + k*H, interpolated,\n"
          "                       never forcing a step;\n"
          "                       without --step and --times an adaptive method writes the\n"
          "                       grid of the model's step, or a sample at every accepted\n"
          "                       step when that grid would exceed 1e6 samples (a long span,\n"
          "                       e.g. robertson --tspan 0:1e11) or the model asks for it\n"
          "                       (robertson, hires; 'dynkit info MODEL' says so)\n"
          "  --times LIST         write samples at these times instead: comma-separated\n"
          "                       (0,0.5,2) or @FILE with one time per line; without --tspan\n"
          "                       the run ends at the last time\n"
          "  --max-step H         largest step size (default: the span)\n"
          "  --initial-step H     first step size (default: chosen from the problem)\n"
          "  --max-steps N        stop after N steps (default: 1e7 steps; a fixed-step run\n"
          "                       whose grid has more is refused before its first step;\n"
          "                       cvode: CVODE's limit between two samples, default 100000;\n"
          "                       when cvode samples every step, a limit on the whole run)\n"
          "  --jac-pattern model|probe|none\n"
          "                       the entries of the Jacobian that stiff methods factor:\n"
          "                       model (default): the model's own (a model file's exact\n"
          "                       pattern, a C model's jac_pattern); probe: those not zero\n"
          "                       at 3 points near the initial state, for a model without\n"
          "                       one, the Jacobian then by differences in groups of\n"
          "                       columns (an entry zero at all 3 points is missed: see\n"
          "                       docs/stiff.md); none: dense matrices\n"
          "  with animate and plot these options are accepted when the main run or a\n"
          "  --compare run is adaptive; fixed-step runs ignore them\n"
          "Events (any method but cvode):\n"
          "  --event NAME[:stop|:continue]\n"
          "                       locate the model's event NAME (repeatable; 'dynkit info\n"
          "                       MODEL' lists them); the run ends at it when the model\n"
          "                       declares it terminal, or with :stop (:continue: never).\n"
          "                       Events that reset the state (XPPAUT's global) take part in\n"
          "                       every run; --event NAME reports them too\n"
          "Poincare maps (any method but cvode; docs/analysis.md, \"Poincare maps\"):\n"
          "  --section SPEC       write the crossings of a section instead of the samples\n"
          "                       (default: the model file's @ poimap): NAME=VALUE[:+|:-|:both]\n"
          "                       a state or output crossing VALUE rising (default), falling\n"
          "                       or both ways; t=T every T (a stroboscope); max:NAME,\n"
          "                       min:NAME, extrema:NAME a state's maxima, minima or both;\n"
          "                       period:NAME=VALUE[:+|:-] the time since the last crossing\n"
          "                       in the column t; :stop ends the run at the first crossing;\n"
          "                       none: the samples, whatever the model file asks\n"
          "Noise (models with wiener, normal or ran; docs/solvers.md, \"Noise\"):\n"
          "  --seed S             the noise of the run, a whole number 0..2^64-1 (default 0):\n"
          "                       the same seed gives the same noise on any machine\n"
          "                       --method euler is Euler-Maruyama (fixed --step), rkmil\n"
          "                       Runge-Kutta Milstein (strong order 1, --rtol/--atol),\n"
          "                       sriw1 Roessler's SRIW1 (strong order 1.5, --rtol/--atol)\n"
          "Volterra integrals (models with int{...} or volt; docs/model-files.md):\n"
          "                       --method volterra, XPPAUT's implicit method on the grid\n"
          "                       of --step, the only method such a model takes\n",
          out);
}

void cli_run_options_help(FILE *out)
{
    run_options_common(out);
    fputs("Output options:\n"
          "  -o, --output FILE    write to FILE instead of standard output ('-'), in the format\n"
          "                       of its extension: .csv, .json, .npy, .npz, .mat (see\n"
          "                       docs/data-files.md)\n"
          "  --events-output FILE write the events of --event to FILE as CSV:\n"
          "                       event,t,<states> (default: on stderr)\n"
          "  --header names|units|none  the CSV header: names (default), 'name [unit]', none\n"
          "  --final              write the header and the last sample only\n"
          "  --every K            keep every K-th sample (the last one is always kept)\n"
          "  --outputs            add the model's extra outputs (energy, ...) as columns\n"
          "  --trace N            print each stage of the first N steps on stderr\n"
          "  --stats              print the counts on stderr: steps=N accepted=N rejected=N rhs=N\n"
          "                       (+ jac=N for stiff methods, and jac_fd_columns=N when\n"
          "                       columns of the exact Jacobian were not finite and were\n"
          "                       formed by differences instead)\n"
          "  --quiet              no progress display on stderr\n",
          out);
}

void cli_view_options_help(FILE *out)
{
    run_options_common(out);
    fputs("Output options:\n"
          "  --every K            keep every K-th sample (the first and the last are kept)\n"
          "  --quiet              no warnings and no progress display on stderr\n",
          out);
}

/* An unknown option, with the nearest run option when it looks like a typo. */
static int unknown_option(const char *command, const char *arg)
{
    static const char *const options[] = {
        "--method", "--step",  "--tspan",  "--end",          "--set",          "--init",
        "--forces", "--interp", "--output", "--header",      "--every",        "--trace",
        "--rtol",   "--atol",  "--times",  "--max-step",     "--initial-step", "--max-steps",
        "--event",  "--events-output",     "--stats",        "--final",        "--outputs",
        "--quiet",  "--compare", "--table", "--seed", "--project-init", "--jac-pattern",
        "--section"};
    char word[64];
    snprintf(word, sizeof word, "%s%.*s", strncmp(arg, "--", 2) == 0 ? "" : "--",
             (int)strcspn(arg, "="), arg);
    const char *near = dyn_lang_nearest(word, options, (int)(sizeof options / sizeof *options));
    if (near && !(strcmp(command, "run") == 0 && strcmp(near, "--compare") == 0))
        return cli_usage_error(command, "unknown option '%s' (did you mean '%s'?)", arg, near);
    return cli_usage_error(command, "unknown option '%s'", arg);
}

static int parse_option(const char *command, int argc, char **argv, int *i, cli_run *run,
                        assignment *as, int *n_as, const char **method_name, unsigned *given)
{
    const char *v = NULL;
    const char *arg = argv[*i];
    int r;
#define OPT(name)                                                                      \
    ((r = cli_option(argc, argv, i, name, &v)) < 0                                     \
         ? (cli_usage_error(command, "option --%s needs a value", name), 1) : r == 1)
    if (OPT("method")) {
        if (r < 0)
            return CLI_USAGE;
        *method_name = v;
        *given |= GIVEN_METHOD;
    } else if (OPT("step")) {
        if (r < 0)
            return CLI_USAGE;
        if (cli_parse_number(v, &run->step) || !(run->step > 0))
            return cli_usage_error(command,
                                   "--step '%s' is not accepted: give a step size in s, a "
                                   "finite number > 0 (e.g. 0.01)",
                                   v);
        *given |= GIVEN_STEP;
    } else if (OPT("tspan")) {
        if (r < 0 || cli_parse_tspan(command, v, &run->t0, &run->t1))
            return CLI_USAGE;
        *given |= GIVEN_TSPAN;
    } else if (OPT("end")) {
        if (r < 0)
            return CLI_USAGE;
        if (strcmp(v, "exact") == 0)
            run->end = DYN_END_EXACT;
        else if (strcmp(v, "grid") == 0)
            run->end = DYN_END_GRID;
        else
            return cli_usage_error(command, "--end '%s' is not accepted (accepted: exact, grid)", v);
    } else if (OPT("set")) {
        if (r < 0)
            return CLI_USAGE;
        as[(*n_as)++] = (assignment){v, 1};
    } else if (OPT("init")) {
        if (r < 0)
            return CLI_USAGE;
        as[(*n_as)++] = (assignment){v, 0};
    } else if (OPT("table")) {
        if (r < 0)
            return CLI_USAGE; /* taken before the model was opened (cli_model_table_options) */
    } else if (OPT("forces")) {
        if (r < 0)
            return CLI_USAGE;
        run->forces_path = v;
    } else if (OPT("interp")) {
        if (r < 0)
            return CLI_USAGE;
        if (strcmp(v, "hold") == 0)
            run->interp = DYN_INTERP_HOLD;
        else if (strcmp(v, "linear") == 0)
            run->interp = DYN_INTERP_LINEAR;
        else
            return cli_usage_error(command,
                                   "--interp '%s' is not accepted (accepted: hold, linear)", v);
        *given |= GIVEN_INTERP;
    } else if (OPT("output")) {
        if (r < 0)
            return CLI_USAGE;
        run->output_path = v;
    } else if (OPT("header")) {
        if (r < 0)
            return CLI_USAGE;
        if (strcmp(v, "names") == 0)
            run->header = CLI_HEADER_NAMES;
        else if (strcmp(v, "units") == 0)
            run->header = CLI_HEADER_UNITS;
        else if (strcmp(v, "none") == 0)
            run->header = CLI_HEADER_NONE;
        else
            return cli_usage_error(command,
                                   "--header '%s' is not accepted (accepted: names, units, none)",
                                   v);
    } else if (OPT("every")) {
        if (r < 0)
            return CLI_USAGE;
        if (cli_parse_count(v, 1, &run->every))
            return cli_usage_error(command, "--every '%s' is not accepted: give a whole number >= 1",
                                   v);
    } else if (OPT("trace")) {
        if (r < 0)
            return CLI_USAGE;
        if (cli_parse_count(v, 0, &run->trace_steps))
            return cli_usage_error(command,
                                   "--trace '%s' is not accepted: give the number of steps to "
                                   "trace, a whole number >= 0",
                                   v);
    } else if (OPT("rtol")) {
        if (r < 0 || cli_parse_tolerance(command, "--rtol", v, run->model->n_states, &run->rtol,
                                     &run->rtolv))
            return CLI_USAGE;
        *given |= GIVEN_RTOL;
    } else if (OPT("atol")) {
        if (r < 0 || cli_parse_tolerance(command, "--atol", v, run->model->n_states, &run->atol,
                                     &run->atolv))
            return CLI_USAGE;
        *given |= GIVEN_ATOL;
    } else if (OPT("times")) {
        if (r < 0 || cli_parse_times(command, v, run))
            return CLI_USAGE;
    } else if (OPT("max-step")) {
        if (r < 0 || cli_parse_positive(command, "--max-step", v, &run->max_step))
            return CLI_USAGE;
        *given |= GIVEN_MAX_STEP;
    } else if (OPT("initial-step")) {
        if (r < 0 || cli_parse_positive(command, "--initial-step", v, &run->initial_step))
            return CLI_USAGE;
        *given |= GIVEN_INITIAL_STEP;
    } else if (OPT("max-steps")) {
        if (r < 0)
            return CLI_USAGE;
        if (cli_parse_count(v, 1, &run->max_steps))
            return cli_usage_error(command,
                                   "--max-steps '%s' is not accepted: give a whole number >= 1",
                                   v);
        *given |= GIVEN_MAX_STEPS;
    } else if (OPT("event")) {
        if (r < 0 || cli_add_event(command, v, run))
            return CLI_USAGE;
    } else if (OPT("section")) {
        if (r < 0 || cli_parse_section(command, v, run))
            return CLI_USAGE;
    } else if (OPT("events-output")) {
        if (r < 0)
            return CLI_USAGE;
        run->events_path = v;
    } else if (OPT("jac-pattern")) {
        if (r < 0)
            return CLI_USAGE;
        run->jac_pattern = v; /* checked and applied once the method is known */
    } else if (cli_flag(arg, "stats")) {
        run->stats = 1;
    } else if (cli_flag(arg, "final")) {
        run->final_only = 1;
    } else if (OPT("seed")) {
        if (r < 0)
            return CLI_USAGE;
        char *end = NULL;
        errno = 0;
        const unsigned long long sd = strtoull(v, &end, 10);
        if (end == v || *end || errno || v[0] == '-')
            return cli_usage_error(command, "--seed '%s': give a whole number 0..2^64-1", v);
        run->seed = (uint64_t)sd;
        *given |= GIVEN_SEED;
    } else if (cli_flag(arg, "outputs")) {
        run->with_outputs = 1;
    } else if (cli_flag(arg, "quiet")) {
        run->quiet = 1;
    } else if (cli_flag(arg, "project-init")) {
        run->project_init = 1;
    } else {
        return unknown_option(command, arg);
    }
#undef OPT
    return CLI_OK;
}

/* A model with noise takes euler (Euler–Maruyama), rkmil or sriw1, a seed, no output times;
 * rkmil and sriw1 need noise, --seed noise or a table of random numbers; sriw1 locates no
 * events. */
static int check_noise_options(const char *command, cli_run *run, unsigned given)
{
    const dyn_model *m = run->model;
    const int adaptive = cli_method_is_sde_adaptive(run->method);
    const char *name = run->method->name;
    if (m->n_noise == 0) {
        if (adaptive)
            return cli_usage_error(command, "--method %s integrates models with noise "
                                   "(wiener, normal, ran), and %s has none: use dp45 (or "
                                   "another method of 'dynkit methods')", name, m->name);
        if ((given & GIVEN_SEED) && !m->seed_offset)
            return cli_usage_error(command, "--seed chooses the noise of a model with noise "
                                   "(wiener, normal, ran) or its tables' random numbers, and "
                                   "%s has none", m->name);
        return CLI_OK;
    }
    if (dyn_method_is_map(run->method))
        return CLI_OK; /* a discrete map draws its noise once per step (and has no events) */
    if (!adaptive && strcmp(name, "euler") != 0)
        return cli_usage_error(command, "model %s has noise (wiener, normal or ran), which "
                               "--method %s cannot integrate: use euler (Euler-Maruyama, "
                               "fixed --step), rkmil (Runge-Kutta Milstein, strong order 1, "
                               "adaptive) or sriw1 (Roessler's SRIW1, strong order 1.5, "
                               "adaptive)", m->name, name);
    if (adaptive && m->noise_class == DYN_NOISE_GENERAL)
        return cli_usage_error(command, "--method %s needs noise that enters the equations "
                               "as c*w with Wiener noise w, additive or one noise per state "
                               "(no normal() or ran()); model %s has other noise: use euler "
                               "(Euler-Maruyama)", name, m->name);
    if (cli_sde_method(run->method) == DYN_SDE_SRIW1 && (run->n_events > 0 || m->n_events > 0))
        return cli_usage_error(command, "--method sriw1 does not locate events, and model %s "
                               "has events (global) or --event asks for them: use rkmil or "
                               "euler", m->name);
    if (run->times)
        return cli_usage_error(command, "--times: a model with noise writes the grid of --step "
                               "(euler: every step; rkmil, sriw1: steps land on it)");
    return CLI_OK;
}

/* A model with Volterra integrals runs with the volterra method only (XPPAUT's), on the
 * grid of --step, without events or output times; the method needs such a model. */
static int check_volterra_options(const char *command, cli_run *run)
{
    const dyn_model *m = run->model;
    const int volterra = cli_method_is_volterra(run->method);
    if (!m->volterra) {
        if (volterra)
            return cli_usage_error(command, "--method volterra integrates models with Volterra "
                                   "integrals (int{...}, volt), and %s has none: use dp45 (or "
                                   "another method of 'dynkit methods')", m->name);
        return CLI_OK;
    }
    if (!volterra)
        return cli_usage_error(command, "model %s has Volterra integrals (int{...}) or integral "
                               "equations (volt), which --method %s cannot integrate: use "
                               "volterra (XPPAUT's implicit method on the grid of --step)",
                               m->name, run->method->name);
    if (run->n_events > 0 || cli_run_resets(run) > 0)
        return cli_usage_error(command, "--event and globals: the volterra method does not "
                               "locate events");
    if (run->times)
        return cli_usage_error(command, "--times: a model with Volterra integrals writes the "
                               "grid of --step");
    return CLI_OK;
}

/* Options that only make sense with some methods, and --times against the span.
 * other_adaptive: another run of the command (--compare) is adaptive. */
static int check_method_options(const char *command, cli_run *run, unsigned given,
                                int other_adaptive)
{
    const dyn_tableau *mt = run->method;
    const int adaptive = dyn_method_is_adaptive(mt);
    const int view = strcmp(command, "run") != 0; /* animate, plot: --compare runs */
    static const struct {
        unsigned flag;
        const char *name;
    } adaptive_only[] = {{GIVEN_RTOL, "--rtol"},
                         {GIVEN_ATOL, "--atol"},
                         {GIVEN_MAX_STEP, "--max-step"},
                         {GIVEN_INITIAL_STEP, "--initial-step"},
                         {GIVEN_MAX_STEPS, "--max-steps"}};
    for (size_t i = 0; i < sizeof adaptive_only / sizeof adaptive_only[0] && !adaptive &&
                       !other_adaptive;
         i++)
        if (adaptive_only[i].flag == GIVEN_MAX_STEPS && !dyn_method_is_map(mt))
            continue; /* a fixed-step run has the limit too */
        else if ((given & adaptive_only[i].flag) && dyn_method_is_map(mt))
            return cli_usage_error(command, "%s applies to adaptive methods only: %s iterates "
                                   "a discrete map, which has no error to control",
                                   adaptive_only[i].name, mt->name);
        else if (given & adaptive_only[i].flag)
            return cli_usage_error(command,
                                   "%s applies to adaptive methods only: %s takes fixed steps of "
                                   "--step H. Give --method dp45 (or bs23, dop853, rodas4) to "
                                   "control the error, or choose the accuracy of %s with "
                                   "--step%s",
                                   adaptive_only[i].name, mt->name, mt->name,
                                   view ? " (it is accepted when the main run or a --compare "
                                          "run is adaptive)"
                                        : "");
    const dyn_tableau *model_method = cli_method_find(cli_model_method(run->model));
    if (dyn_method_is_map(model_method) != dyn_method_is_map(mt))
        return cli_usage_error(command,
                               dyn_method_is_map(mt)
                                   ? "--method %s iterates a discrete map, and %s is a "
                                     "differential equation: give an integrator (its default "
                                     "is %s)"
                                   : "--method %s integrates differential equations, and %s is "
                                     "a discrete map (x(t+1)=..., or meth=discrete): it runs "
                                     "with its own method, %s",
                               mt->name, run->model->name, cli_model_method(run->model));
    if (dyn_method_is_map(mt) && (run->n_events > 0 || cli_run_resets(run) > 0))
        return cli_usage_error(command,
                               "%s is a discrete map: its states jump from step to step, so "
                               "there are no events or resets to locate between them (write "
                               "every step and look at the rows)",
                               run->model->name);
    if (cli_method_is_cvode(mt) && run->n_events > 0)
        return cli_usage_error(command,
                               "--event is not available with --method cvode: the CVODE "
                               "backend runs without root finding here. Locate events with "
                               "--method rodas4 (stiff) or dp45");
    if (cli_method_is_cvode(mt) && run->trace_steps > 0)
        return cli_usage_error(command,
                               "--trace prints the stages of a Runge-Kutta step; cvode is a "
                               "multistep (BDF) method and has none (--stats gives its "
                               "counts)");
    if (dyn_method_is_map(mt) && (given & GIVEN_STEP) && run->step != 1.0)
        return cli_usage_error(command,
                               "--step %s: a discrete map steps by 1 (t counts its steps, as in "
                               "XPPAUT); give --tspan to choose how many",
                               CLI_NUM(run->step));
    dyn_grid map_grid;
    if (dyn_method_is_map(mt) &&
        dyn_grid_plan(run->t0, run->t1, run->step, run->end, &map_grid, NULL, 0) == DYN_OK &&
        map_grid.partial)
        return cli_usage_error(command,
                               "a discrete map takes whole steps: the span %s:%s is not a whole "
                               "number of steps of %s (give such a span, or --end grid to stop "
                               "at the last whole step)",
                               CLI_NUM(run->t0), CLI_NUM(run->t1), CLI_NUM(run->step));
    if (run->times && dyn_method_is_map(mt))
        return cli_usage_error(command,
                               "--times: a discrete map has states only at its steps t0, t0 + "
                               "1, ... (give --every K to write every K-th)");
    if (run->times && !adaptive)
        return cli_usage_error(command,
                               "--times needs an adaptive method (e.g. --method dp45), whose "
                               "dense output gives the state at any time; %s writes the samples "
                               "t0 + k*step",
                               mt->name);
    if (run->times && (given & GIVEN_STEP))
        return cli_usage_error(command,
                               "give either --step (samples at T0 + k*H) or --times, not both");
    if (run->events_path && run->n_events == 0)
        return cli_usage_error(command, "--events-output needs --event NAME (which events to "
                                        "write)");
    cli_format events_format;
    char ferr[512];
    if (run->events_path &&
        (cli_format_of_path(run->events_path, &events_format, ferr, sizeof ferr) ||
         events_format != CLI_FORMAT_CSV))
        return cli_usage_error(command,
                               "--events-output '%s': the events are written as CSV "
                               "(event,t,<states>): give FILE.csv, or '-' for standard output",
                               run->events_path);
    if (run->times) {
        const double first = run->times[0], last = run->times[run->n_times - 1];
        if (!(given & GIVEN_TSPAN)) {
            if (!(last > run->t0))
                return cli_usage_error(command,
                                       "--times: the last time %s must be after the start "
                                       "time %s (or give --tspan)",
                                       CLI_NUM(last), CLI_NUM(run->t0));
            run->t1 = last;
        }
        if (first < run->t0 || last > run->t1)
            return cli_usage_error(command,
                                   "--times: the times must lie in the span %s:%s (got "
                                   "%s .. %s)",
                                   CLI_NUM(run->t0), CLI_NUM(run->t1), CLI_NUM(first),
                                   CLI_NUM(last));
    }
    return CLI_OK;
}

/* A Poincaré section is an event of the run: the methods and models that locate events. */
static int check_section_options(const char *command, cli_run *run)
{
    if (run->section.kind == DYN_POINCARE_NONE)
        return CLI_OK;
    const char *from = run->section_given ? "--section" : "the model's @ poimap";
    if (cli_method_is_cvode(run->method))
        return cli_usage_error(command, "%s: the section is located as an event, and cvode "
                               "runs without events here: use rodas4 (stiff) or dp45", from);
    if (dyn_method_is_map(run->method))
        return cli_usage_error(command, "%s: a discrete map has no crossings between its "
                               "steps to locate", from);
    if (run->model->volterra)
        return cli_usage_error(command, "%s: the volterra method does not locate events", from);
    if (cli_sde_method(run->method) == DYN_SDE_SRIW1)
        return cli_usage_error(command, "%s: --method sriw1 does not locate events: use rkmil",
                               from);
    return CLI_OK;
}

/* --verbose: the method and tolerances of the run and where each came from. */
static void note_method(const cli_run *run, unsigned given)
{
    const dyn_model *m = run->model;
    char b[3][96];
    cli_stderr("dynkit: note: method %s (%s)", run->method->name,
               given & GIVEN_METHOD ? "--method"
                                    : cli_model_default_source(m, CLI_DEFAULT_METHOD, b[0], 96));
    if (dyn_method_is_adaptive(run->method) && !run->rtolv && !run->atolv)
        cli_stderr(", rtol %s (%s), atol %s (%s)", CLI_NUM(run->rtol),
                   given & GIVEN_RTOL ? "--rtol"
                                      : cli_model_default_source(m, CLI_DEFAULT_RTOL, b[1], 96),
                   CLI_NUM(run->atol),
                   given & GIVEN_ATOL ? "--atol"
                                      : cli_model_default_source(m, CLI_DEFAULT_ATOL, b[2], 96));
    else if (dyn_method_is_adaptive(run->method))
        cli_stderr(", per-state tolerances (--rtol/--atol)");
    else
        cli_stderr(", step %s", CLI_NUM(run->step));
    fputc('\n', stderr);
    if (dyn_method_is_stiff(run->method)) {
        cli_linear lin;
        cli_linear_for_run(run, &lin);
        cli_note("%s", lin.why);
    }
}

/* The model's tolerances when --rtol/--atol are not given (every method, cvode too: its own,
 * or DYN_MODEL_RTOL and DYN_MODEL_ATOL); a relative tolerance below rounding raised to
 * DYN_MIN_RTOL with a warning; the default limit on the steps of adaptive runs. */
static void tolerance_defaults(cli_run *run, unsigned given)
{
    const dyn_model *m = run->model;
    if (!(given & GIVEN_RTOL))
        run->rtol = cli_model_rtol(m);
    if (!(given & GIVEN_ATOL))
        run->atol = cli_model_atol(m);
    int raised = run->rtol > 0.0 && run->rtol < DYN_MIN_RTOL;
    if (raised)
        run->rtol = DYN_MIN_RTOL;
    for (int i = 0; run->rtolv && i < m->n_states; i++)
        if (run->rtolv[i] > 0.0 && run->rtolv[i] < DYN_MIN_RTOL) {
            run->rtolv[i] = DYN_MIN_RTOL;
            raised = 1;
        }
    if (raised && dyn_method_is_adaptive(run->method))
        cli_warning("--rtol below rounding asks for more than doubles can give; "
                "raised to %.3g (100 eps, as MATLAB)",
                DYN_MIN_RTOL);
    if (!(given & GIVEN_MAX_STEPS) && !dyn_method_is_map(run->method) &&
        !cli_method_is_cvode(run->method))
        run->max_steps = CLI_DEFAULT_MAX_STEPS;
    if (cli_verbose())
        note_method(run, given);
}

/* The initial state, named when it cannot start a run: a state that is not finite (a
 * default that follows the parameters, such as the plane's l0 + m g/k with k = 0), and a
 * zero attitude quaternion (states qw, qx, qy, qz). */
static int check_initial_state(const char *command, cli_run *run)
{
    const dyn_model *m = run->model;
    for (int i = 0; i < m->n_states; i++)
        if (!isfinite(run->y0[i]))
            return cli_usage_error(command,
                                   "the initial state %s = %g is not finite%s: give --init "
                                   "%s=VALUE or other parameters",
                                   m->states[i].name, run->y0[i],
                                   m->initial_state ? " (its default follows the parameters)"
                                                    : "",
                                   m->states[i].name);
    const int qw = dyn_model_state_index(m, "qw"), qx = dyn_model_state_index(m, "qx"),
              qy = dyn_model_state_index(m, "qy"), qz = dyn_model_state_index(m, "qz");
    if (qw >= 0 && qx >= 0 && qy >= 0 && qz >= 0 && run->y0[qw] == 0.0 && run->y0[qx] == 0.0 &&
        run->y0[qy] == 0.0 && run->y0[qz] == 0.0)
        return cli_usage_error(command,
                               "the attitude quaternion (qw, qx, qy, qz) is zero: it has no "
                               "orientation; give a non-zero one, e.g. --init qw=1");
    return CLI_OK;
}

int cli_run_parse(const char *command, int argc, char **argv, cli_run *run)
{
    return cli_run_parse_with(command, argc, argv, 0, run);
}

int cli_run_parse_with(const char *command, int argc, char **argv, int other_adaptive,
                       cli_run *run)
{
    char names[512], err[256];
    memset(run, 0, sizeof *run);
    if (argc < 1 || argv[0][0] == '-')
        return cli_usage_error(command, "missing MODEL (accepted: %s)",
                               dyn_model_names(names, sizeof names));
    int open_rc = cli_model_table_options(command, argc, argv);
    int project = 0;
    for (int i = 1; i < argc; i++)
        project |= cli_flag(argv[i], "project-init");
    if (project && !cli_has_extension(argv[0], ".mech"))
        return cli_usage_error(command, "--project-init needs a mechanism file (NAME.mech): "
                               "only a mechanism's constraints are known");
    cli_model_set_unchecked(project); /* the state is projected before the run */
    if (open_rc == CLI_OK)
        open_rc = cli_model_open(command, argv[0], &run->model);
    cli_model_set_unchecked(0);
    if (open_rc != CLI_OK)
        return open_rc;
    const dyn_model *m = run->model;
    run->par = calloc(1, m->par_size);
    run->y0 = calloc((size_t)m->n_states, sizeof *run->y0);
    assignment *as = calloc((size_t)argc, sizeof *as);
    if (!run->par || !run->y0 || !as) {
        free(as);
        cli_error("out of memory");
        return CLI_FAILED;
    }
    dyn_model_default_params(m, run->par, err, sizeof err);
    run->t0 = m->t0;
    run->t1 = m->t1;
    run->step = m->step;
    run->every = m->every > 1 ? m->every : 1; /* a model file's @ nout */
    const char *method_name = cli_model_method(m);
    int n_as = 0, rc = CLI_OK;
    unsigned given = 0;
    for (int i = 1; i < argc && rc == CLI_OK; i++)
        rc = parse_option(command, argc, argv, &i, run, as, &n_as, &method_name, &given);
    /* parameters first: the default initial state may depend on them; then --init. The
     * --set numbers before the --set formulas, each formula of the values set before it
     * (docs/cli.md, "Numbers") */
    cli_formula_params(m, run->par);
    for (int pass = 0; pass < 2; pass++)
        for (int k = 0; k < n_as && rc == CLI_OK; k++)
            if (as[k].is_param && cli_assignment_is_number(&as[k]) == (pass == 0))
                rc = cli_apply_assignment(command, run, &as[k]);
    if (m->seed_offset) { /* the tables' random numbers: drawn in prepare */
        double *sd = (double *)((char *)run->par + m->seed_offset);
        sd[0] = (double)(uint32_t)run->seed;
        sd[1] = (double)(uint32_t)(run->seed >> 32);
    }
    if (rc == CLI_OK && m->prepare && m->prepare(run->par, err, sizeof err))
        rc = cli_usage_error(command, "%s", err);
    if (rc == CLI_OK)
        dyn_model_initial_state(m, run->par, run->y0);
    for (int k = 0; k < n_as && rc == CLI_OK; k++)
        if (!as[k].is_param)
            rc = cli_apply_assignment(command, run, &as[k]);
    free(as);
    if (rc == CLI_OK)
        rc = check_initial_state(command, run);
    /* a mechanism's constraints at the state the options made (the file's own initial
     * state was checked when it was read); `continue` solves the states the constraints
     * determine from the others at every point, as `steady` does, so its --init values
     * need not hold them */
    if (rc == CLI_OK && cli_has_extension(argv[0], ".mech") && (run->project_init || n_as > 0) &&
        strcmp(command, "continue") != 0)
        rc = cli_mech_initial(command, argv[0], run, run->project_init);
    if (rc != CLI_OK)
        return rc;
    if ((given & GIVEN_INTERP) && !run->forces_path)
        return cli_usage_error(command, "--interp needs --forces FILE (a table to read)");
    if (run->forces_path && (rc = cli_load_input(command, run, given)) != CLI_OK)
        return rc;
    run->method = cli_method_find(method_name);
    if (!run->method)
        return cli_method_error(command, "--method", method_name);
    run->step_given = (given & GIVEN_STEP) || run->forces_path;
    rc = cli_run_jac_pattern(command, run);
    if (rc == CLI_OK)
        rc = check_noise_options(command, run, given);
    if (rc == CLI_OK)
        rc = check_volterra_options(command, run);
    if (rc == CLI_OK)
        rc = check_method_options(command, run, given, other_adaptive);
    if (rc == CLI_OK)
        rc = cli_section_from_model(command, run);
    if (rc == CLI_OK)
        rc = check_section_options(command, run);
    if (rc == CLI_OK)
        tolerance_defaults(run, given);
    return rc;
}

void cli_run_free(cli_run *run)
{
    free(run->par);
    free(run->y0);
    free(run->input);
    free(run->rtolv);
    free(run->atolv);
    free(run->times);
    free(run->events);
    free(run->own_model);
    cli_section_free(run);
    dyn_sparse_pattern_free(&run->probed);
    run->own_model = NULL;
    run->par = NULL;
    run->y0 = NULL;
    run->input = NULL;
    run->rtolv = run->atolv = run->times = NULL;
    run->events = NULL;
}
