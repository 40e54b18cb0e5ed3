/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit continue MODEL --par NAME [--par2 NAME] [--init/--set ...] [--at NAME=V1,...]
 * [--opt NAME=VALUE] [--output FILE.csv|.json|.svg|.html] [--json] [--svg FILE]
 * [--html FILE]: the bifurcation diagram of a model (dyn_continue, dynkit/continuation.h)
 * with XPPAUT's AUTO settings from the model file's @ lines, written as a summary of the
 * special points, a CSV table of every point, JSON, an SVG picture and a page that shows
 * the periodic orbits (cont_output.c, cont_svg.c, cont_page.c). docs/analysis.md,
 * "Continuation". */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "dynkit/colloc.h"
#include "commands/analysis_kinds.h"
#include "commands/cont_steady.h"
#include "commands/eq_box.h"
#include "dynkit/equilibria.h"
#include "cont_output.h"
#include "cont_settings.h"
#include "util/out_file.h"

#define CONT_MAX_AT 1000L

static void continue_help(void)
{
    puts("Usage: dynkit continue MODEL --par NAME [--par2 NAME] [--init NAME=VALUE]...\n"
         "                       [--set NAME=VALUE]... [--at NAME=V1,V2,...]\n"
         "                       [--opt NAME=VALUE]... [--output FILE]\n"
         "                       [--json] [--svg FILE.svg] [--html FILE.html] [--y NAME]\n"
         "                       [--unknown NAME,...] [--cyclic NAME,...]\n"
         "\n"
         "Follows the equilibria f(x, p) = 0 of MODEL in the parameter NAME by pseudo-\n"
         "arclength continuation from the model's initial state (with the --init values),\n"
         "made an equilibrium by Newton's method first (when none is near it, the end of a\n"
         "run over the model's span is, else the equilibrium nearest the initial state\n"
         "among those `equilibria` finds in its default box, with a note). Folds (LP), Hopf\n"
         "points (HB, with the first Lyapunov coefficient l1: supercritical when l1 < 0,\n"
         "subcritical when l1 > 0),\n"
         "branch points (BP; the other branch, its direction from the algebraic branching\n"
         "equation, is followed both ways) are located to 1e-10 in the parameter; the\n"
         "branch's ends are EP, the values of --at are UZ; a branch that comes back to its\n"
         "first or a labelled point is closed and ends there. From each Hopf point the\n"
         "periodic orbits by collocation, with folds of cycles (LPC), period doublings (PD;\n"
         "the doubled branch is followed), torus bifurcations (TR) and branch points of\n"
         "cycles (BP: a multiplier through +1 where the branch does not fold; the other\n"
         "family is followed both ways). With --par2,\n"
         "the curves of folds and of Hopf points through each LP and HB are followed in the\n"
         "two parameters, with cusps (CP), Bogdanov-Takens (BT), generalized Hopf (GH) and\n"
         "fold-Hopf (ZH) points located.\n"
         "\n"
         "A discrete map (an .ode file with x(t+1)= lines: XPPAUT's meth=discrete): its\n"
         "fixed points F(y, p) = y are followed instead, stable when every multiplier\n"
         "(eigenvalue of dF/dy) has |mu| < 1, with LP (mu = 1), BP (switched as above), PD\n"
         "(a real multiplier through -1) and TR (a complex pair through the unit circle:\n"
         "Neimark-Sacker, AUTO-07p's label for maps; its angle arg mu is printed); the\n"
         "JSON gives \"map\": true and each point's \"multipliers\". The file's @ njmp=k\n"
         "(XPPAUT's period of a map for AUTO) makes them the points of period k (fixed\n"
         "points of F^k). From each PD the\n"
         "points of twice the period (fixed points of F o F) are followed, up to period\n"
         "16; the period column gives the points' period. With --par2, the curves of\n"
         "its folds, flips (kind flip) and Neimark-Sacker points (kind neimark-sacker,\n"
         "with their angle) in the two parameters.\n"
         "\n"
         "A mechanism file (.mech) with constraints or cyclic coordinates: a steady motion\n"
         "(dynkit steady's equations) is followed instead, the state at each value the\n"
         "file's initial state there with the unknowns solved; stability, HB and BP (a real\n"
         "eigenvalue through zero where the branch does not fold) come from the reduced\n"
         "linearization without the family's and the cyclic coordinates' zero eigenvalues;\n"
         "at a BP where another family of steady motions crosses (the bicycle's steady\n"
         "turns at its capsize speed), that branch is followed both ways. HH (Hamiltonian\n"
         "Hopf): two imaginary pairs of a conservative steady motion collide and leave the\n"
         "axis (the sleeping top below its critical spin), with the frequency there.\n"
         "With --par2, the curves of its folds and Hopf points in the two parameters.\n"
         "\n"
         "Settings (XPPAUT's AUTO names): a model file's @ lines give them (ntst, ncol, nmax,\n"
         "npr, ds, dsmin, dsmax, parmin, parmax, autoxmin, autoxmax, autoymin, autoymax;\n"
         "autovar: the state on the diagram's y axis unless --y names one),\n"
         "--opt NAME=VALUE overrides them, and the rest are XPPAUT's defaults: ds=0.02\n"
         "(its sign is the direction), dsmin=0.001, dsmax=0.5, nmax=200, parmin=0, parmax=2;\n"
         "par2min, par2max bound the second parameter (default: none). When neither the\n"
         "file nor --opt gives parmin (parmax) and the start is below (above) it, it is\n"
         "moved so that the start is the window's middle, at least the default width 2\n"
         "away, and a note says so; a parmin or parmax given that excludes the start is an\n"
         "error.\n"
         "\n"
         "Options:\n"
         "  --par NAME           the parameter continued (required)\n"
         "  --par2 NAME          a second parameter: curves of folds and Hopf points\n"
         "  --init NAME=VALUE    a state of the starting guess (repeatable; a mechanism's\n"
         "                       need not hold its constraints: the states they determine\n"
         "                       are solved from the others)\n"
         "  --set NAME=VALUE     a parameter's value (repeatable); --par's is the start\n"
         "  --at NAME=V1,V2,...  points computed at these values of the parameter (UZ);\n"
         "                       NAME=A:B:N for N values from A to B\n"
         "  --opt NAME=VALUE     an AUTO setting (repeatable), over the file's @ lines\n"
         "  --jacobian SCHEME    df/dx: auto (default), analytic, central, richardson\n"
         "  -o, --output FILE    .csv: one row per point: branch, kind, label, the\n"
         "                       parameter(s), the states, min_ of each state (periodic\n"
         "                       orbits: maxima in the state's column, minima in min_),\n"
         "                       period, stable; .json: as --json; .svg: as --svg;\n"
         "                       .html: as --html; '-': CSV on stdout ('-.json', '-.svg',\n"
         "                       '-.html': that format). With a file, nothing is printed\n"
         "                       on standard output\n"
         "  --json               everything as JSON on standard output, with the\n"
         "                       eigenvalues (or Floquet multipliers) of each point\n"
         "  --unknown NAME,...   a mechanism's steady motion: the states solved for\n"
         "                       (default: the steady equations' states whose initial\n"
         "                       value does not follow --par; the others are held)\n"
         "  --cyclic NAME,...    a mechanism's cyclic states (default: found as by steady)\n"
         "  --svg FILE           the diagram: the parameter against a state (--y NAME;\n"
         "                       default the first state), stable solid, unstable dashed,\n"
         "                       periodic orbits by their maximum and minimum, the special\n"
         "                       points labelled, axes with units; with --par2 a second\n"
         "                       panel shows the curves in the two parameters\n"
         "  --html FILE          the diagram as a self-contained page: clicking a dot of a\n"
         "                       periodic branch shows that orbit over one period and in\n"
         "                       the plane of two states\n"
         "\n"
         "Without --output, --json, --svg and --html the special points are printed.\n"
         "\n"
         "Examples:\n"
         "  dynkit continue examples/models/lorenz.ode --par rho --init x=8.5 --init y=8.5 \\\n"
         "      --init z=27 --set rho=28 --opt ds=-0.5 --opt parmin=1 --opt dsmax=1 \\\n"
         "      --opt parmax=40\n"
         "  dynkit continue examples/models/brusselator.ode --par b --opt parmax=4 \\\n"
         "      --output bru.csv\n"
         "  dynkit continue examples/models/brusselator.ode --par b --output bru.html\n"
         "  dynkit continue examples/models/henon.ode --par a --opt ds=-0.02 \\\n"
         "      --opt parmin=-0.5 --opt nmax=40\n"
         "  dynkit continue examples/mechanisms/bicycle.mech --par v --set v=3 \\\n"
         "      --opt parmax=10");
}

typedef struct cont_args {
    const char *par, *par2, *at, *output, *svg, *html, *ynam, *scheme_text, *unknown, *cyclic;
    int json;
    const char *opt[64];
    int n_opt;
    const char *init[256]; /* the --init texts: a mechanism's held states */
    int n_init;
} cont_args;

static int parse_args(int argc, char **argv, char **pass, int *n_pass, cont_args *a)
{
    static const char *const options[] = {"--init", "--set",    "--par",      "--par2",
                                          "--at",   "--output", "--svg",      "--y",
                                          "--opt",  "--json",   "--jacobian", "--unknown",
                                          "--cyclic", "--html"};
    pass[(*n_pass)++] = argv[0];
    for (int i = 1; i < argc; i++) {
        const char *v = NULL;
        int r = 0, done = 0;
        const char *passed[] = {"init", "set"};
        for (int k = 0; k < 2 && !done; k++)
            if ((r = cli_option(argc, argv, &i, passed[k], &v)) != 0) {
                if (r < 0)
                    return cli_usage_error("continue", "option --%s needs a value", passed[k]);
                pass[(*n_pass)++] = (char *)options[k];
                pass[(*n_pass)++] = (char *)v;
                if (k == 0 && a->n_init < 256)
                    a->init[a->n_init++] = v;
                done = 1;
            }
        const char *own[] = {"par", "par2",     "at",      "output", "svg",
                             "y",   "opt",      "jacobian", "unknown", "cyclic", "html"};
        const char **dest[] = {&a->par, &a->par2,        &a->at,      &a->output, &a->svg,
                               &a->ynam, NULL, &a->scheme_text, &a->unknown, &a->cyclic,
                               &a->html};
        for (int k = 0; k < 11 && !done; k++)
            if ((r = cli_option(argc, argv, &i, own[k], &v)) != 0) {
                if (r < 0)
                    return cli_usage_error("continue", "option --%s needs a value", own[k]);
                if (k == 6) {
                    if (a->n_opt == 64)
                        return cli_usage_error("continue", "--opt: at most 64 of them");
                    a->opt[a->n_opt++] = v;
                } else {
                    *dest[k] = v;
                }
                done = 1;
            }
        if (!done && strcmp(argv[i], "-o") == 0) {
            if (i + 1 >= argc)
                return cli_usage_error("continue", "option -o needs a value");
            a->output = argv[++i];
            done = 1;
        }
        if (done)
            continue;
        if (cli_flag(argv[i], "json"))
            a->json = 1;
        else
            return cli_unknown_option("continue", argv[i], options, 14);
    }
    if (!a->par)
        return cli_usage_error("continue", "missing --par NAME (the parameter to continue in)");
    if (a->output && strcmp(a->output, "-") != 0) {
        static const char *const exts[] = {".csv", ".json", ".svg", ".html", ".htm", NULL};
        if (cli_out_check_extension("continue", "--output", a->output, exts) != CLI_OK)
            return CLI_USAGE;
    }
    if (a->svg) {
        static const char *const exts[] = {".svg", NULL};
        if (cli_out_check_extension("continue", "--svg", a->svg, exts) != CLI_OK)
            return CLI_USAGE;
    }
    if (a->html) {
        static const char *const exts[] = {".html", ".htm", NULL};
        if (cli_out_check_extension("continue", "--html", a->html, exts) != CLI_OK)
            return CLI_USAGE;
    }
    return CLI_OK;
}

/* 1 when a page is written: the periodic points then keep their orbits */
static int wants_page(const cont_args *a)
{
    return a->html || (a->output && (cli_has_extension(a->output, ".html") ||
                                     cli_has_extension(a->output, ".htm")));
}

static int param_arg(const dyn_model *m, const char *opt, const char *name, int *ip)
{
    *ip = dyn_model_param_index(m, name);
    if (*ip >= 0)
        return CLI_OK;
    char list[1024] = "";
    size_t used = 0;
    for (int k = 0; k < m->n_params && used + 2 < sizeof list; k++)
        used += (size_t)snprintf(list + used, sizeof list - used, "%s%s", k ? ", " : "",
                                 m->params[k].name);
    return cli_usage_error("continue", "%s '%s': not a parameter of %s (accepted: %s)", opt,
                           name, m->name, m->n_params ? list : "none: the model has none");
}

/* the settings: defaults, the file's @ lines, --opt; par holds the start of --par */
static int settings(const cont_args *a, const void *par, const dyn_model *m, cont_settings *s)
{
    char err[2048];
    for (int k = 0; k < 4; k++)
        s->window[k] = NAN;
    const char *path = cli_model_path(m);
    if (path && cli_has_extension(path, ".ode")) {
        size_t len = 0;
        char *text = cli_read_model_file(path, &len);
        if (!text)
            return CLI_USAGE;
        const int bad = cont_settings_read_file(s, text, len, path, err, sizeof err);
        free(text);
        if (bad)
            return cli_usage_error("continue", "%s", err);
    }
    for (int k = 0; k < a->n_opt; k++) {
        const char *eq = strchr(a->opt[k], '=');
        if (!eq || eq == a->opt[k])
            return cli_usage_error("continue", "--opt '%s': give NAME=VALUE", a->opt[k]);
        char name[64];
        snprintf(name, sizeof name, "%.*s", (int)(eq - a->opt[k]), a->opt[k]);
        if (cont_settings_apply(s, name, eq + 1, "--opt", err, sizeof err))
            return cli_usage_error("continue", "%s", err);
    }
    char note[512];
    if (cont_settings_fit_start(s, dyn_model_get_param(m, par, s->opts.ip), a->par, note,
                                sizeof note, err, sizeof err))
        return cli_usage_error("continue", "%s", err);
    if (note[0])
        cli_note("%s", note);
    const dyn_cont_opts *o = &s->opts;
    if (!(o->dsmin <= o->dsmax))
        return cli_usage_error("continue", "dsmin = %g > dsmax = %g: give dsmin <= dsmax",
                               o->dsmin, o->dsmax);
    if (!(fabs(o->ds) >= o->dsmin && fabs(o->ds) <= o->dsmax))
        return cli_usage_error("continue", "|ds| = %g is not within [dsmin, dsmax] = [%g, %g]",
                               fabs(o->ds), o->dsmin, o->dsmax);
    if (!(o->parmin < o->parmax))
        return cli_usage_error("continue", "parmin = %g >= parmax = %g: give parmin < parmax",
                               o->parmin, o->parmax);
    return CLI_OK;
}

static int parse_scheme(const char *text, dyn_jac_scheme *s)
{
    static const char *const names[] = {"auto", "analytic", "central", "richardson"};
    for (int k = 0; k < 4; k++)
        if (strcmp(text, names[k]) == 0) {
            *s = (dyn_jac_scheme)k;
            return CLI_OK;
        }
    return cli_usage_error("continue",
                           "--jacobian '%s': accepted: auto, analytic, central, richardson", text);
}

static int ignore_sample(long k, double t, const double *y, void *ctx)
{
    (void)k;
    (void)t;
    (void)y;
    (void)ctx;
    return 0;
}

/* No equilibrium near the initial state: as XPPAUT users do (integrate to rest, then start
 * AUTO), the model is run over its span from that state and the branch started from where
 * the run ends, with a note; when that fails too (the run itself, or the branch from its
 * end), the first failure stays in info with a note on the second. The progress line, if
 * one is shown, is cleared before a note. The library's status. */
static int start_from_run(const cli_run *run, const dyn_cont_opts *o, dyn_diagram *d,
                          dyn_cont_info *info, cli_progress *progress)
{
    const dyn_model *m = run->model;
    char first[sizeof info->message];
    snprintf(first, sizeof first, "%s", info->message);
    double *y = malloc((size_t)m->n_states * sizeof *y);
    if (!y)
        return DYN_ERR_ARG;
    dyn_result res;
    memset(&res, 0, sizeof res);
    int ok = cli_run_solve(run, 1, ignore_sample, NULL, NULL, NULL, NULL, NULL, y, &res) == 0;
    int bad = -1; /* a state not finite at the run's end */
    for (int i = 0; ok && i < m->n_states; i++)
        if (!isfinite(y[i])) {
            ok = 0;
            bad = i;
        }
    if (!ok) {
        cli_stderr("dynkit: note: continue: a run from the initial state gives no start "
                   "either: %s\n",
                   bad >= 0 ? "a state is not finite at its end"
                   : res.message[0] ? res.message : "the run failed");
        free(y);
        return DYN_ERR_ARG;
    }
    dyn_diagram_free(d);
    memset(info, 0, sizeof *info);
    const int st = dyn_continue(m, run->par, y, o, d, info);
    free(y);
    cli_progress_finish(progress);
    if (st == 0) {
        cli_stderr("dynkit: note: continue: %s; the branch starts from the end of a run from "
                   "the initial state (t = %s)\n",
                   first, dyn_shortest(res.t).s);
    } else {
        cli_stderr("dynkit: note: continue: the end of a run from the initial state "
                   "(t = %s) is no better: %s\n",
                   dyn_shortest(res.t).s, info->message);
        snprintf(info->message, sizeof info->message, "%s", first);
    }
    return st;
}

/* Neither the initial state nor the end of a run is near an equilibrium (a model that
 * bursts or spikes there): the equilibria in the default box of dynkit equilibria are
 * found, and the branch starts from the one nearest the initial state (distances scaled by
 * the box's widths), with a note naming it. The library's status; on failure info keeps
 * the first message. */
static int start_from_equilibria(const cli_run *run, const dyn_cont_opts *o, dyn_diagram *d,
                                 dyn_cont_info *info, cli_progress *progress)
{
    const dyn_model *m = run->model;
    const int n = m->n_states;
    char first[sizeof info->message];
    snprintf(first, sizeof first, "%s", info->message);
    double *lo = malloc((size_t)n * sizeof *lo), *hi = malloc((size_t)n * sizeof *hi);
    int *from_file = malloc((size_t)n * sizeof *from_file);
    dyn_equilibria e;
    memset(&e, 0, sizeof e);
    int st = DYN_ERR_ARG;
    if (lo && hi && from_file) {
        cli_eq_default_box(run, lo, hi, from_file);
        dyn_equilibria_opts eo;
        memset(&eo, 0, sizeof eo);
        eo.lo = lo;
        eo.hi = hi;
        eo.guess = run->y0;
        eo.map = o->map;
        eo.scheme = o->jac;
        st = dyn_equilibria_find(m, o->t, run->par, &eo, &e);
    }
    int best = -1;
    double best_dist = INFINITY;
    for (int k = 0; st == 0 && k < e.count; k++) {
        double dist = 0.0;
        for (int i = 0; i < n; i++) {
            const double w = hi[i] > lo[i] ? hi[i] - lo[i] : 1.0;
            const double r = (e.y[(size_t)k * n + i] - run->y0[i]) / w;
            dist += r * r;
        }
        if (dist < best_dist) {
            best_dist = dist;
            best = k;
        }
    }
    if (best < 0) {
        cli_progress_finish(progress);
        cli_stderr("dynkit: note: continue: the search of dynkit equilibria in its default "
                   "box finds none at %s = %s either (--init NAME=VALUE gives a start near "
                   "one; dynkit equilibria --box NAME=A:B searches a box)\n",
                   m->params[o->ip].name, dyn_shortest(dyn_model_get_param(m, run->par, o->ip)).s);
        snprintf(info->message, sizeof info->message, "%s", first);
        st = st ? st : DYN_ERR_ARG;
    } else {
        const double *y = e.y + (size_t)best * n;
        dyn_diagram_free(d);
        memset(info, 0, sizeof *info);
        st = dyn_continue(m, run->par, y, o, d, info);
        cli_progress_finish(progress);
        char where[400] = "";
        size_t len = 0;
        for (int i = 0; i < n && len < sizeof where - 1; i++) {
            const int more = i == 6 && n > 7;
            len += (size_t)snprintf(where + len, sizeof where - len, "%s%s", i ? ", " : "",
                                    more ? "..." : "");
            if (more)
                break;
            if (len < sizeof where - 1)
                len += (size_t)snprintf(where + len, sizeof where - len, "%.40s = %s",
                                        m->states[i].name, dyn_shortest(y[i]).s);
        }
        if (st == 0)
            cli_stderr("dynkit: note: continue: the branch starts from the equilibrium nearest the initial state of the %d that "
                       "dynkit equilibria finds in its default box: %s\n",
                       e.count, where);
        else {
            cli_stderr("dynkit: note: continue: the equilibrium nearest the initial state "
                       "found by dynkit equilibria (%s) is no better: %s\n",
                       where, info->message);
            snprintf(info->message, sizeof info->message, "%s", first);
        }
    }
    dyn_equilibria_free(&e);
    free(lo);
    free(hi);
    free(from_file);
    return st;
}

typedef struct continue_progress_ctx {
    const dyn_model *m;
    cli_progress *progress;
} continue_progress_ctx;

/* "branch 3 (periodic): 120 points, a = 1.0964" on a terminal's stderr */
static void continue_progress(const dyn_branch *b, void *ctx)
{
    const continue_progress_ctx *c = ctx;
    if (!c->progress->enabled || b->count < 1)
        return;
    const dyn_branch_point *p = &b->pts[b->count - 1];
    char text[160];
    snprintf(text, sizeof text, "branch %d (%s): %ld points, %.40s = %.6g", b->id,
             dyn_branch_kind_name(b->kind), b->count, c->m->params[b->par_index[0]].name,
             p->par[0]);
    cli_progress_text(c->progress, text);
}

int cli_cmd_continue(int argc, char **argv)
{
    for (int i = 0; i < argc; i++)
        if (cli_is_help(argv[i])) {
            continue_help();
            return CLI_OK;
        }
    if (argc < 1 || argv[0][0] == '-') {
        char names[512];
        return cli_usage_error("continue", "missing MODEL (accepted: %s, or a model file)",
                               dyn_model_names(names, sizeof names));
    }
    char **pass = calloc((size_t)(2 * argc + 1), sizeof *pass);
    if (!pass)
        return CLI_FAILED;
    int n_pass = 0;
    cont_args a;
    memset(&a, 0, sizeof a);
    int rc = parse_args(argc, argv, pass, &n_pass, &a);
    cli_run run;
    memset(&run, 0, sizeof run);
    if (rc == CLI_OK)
        rc = cli_run_parse("continue", n_pass, pass, &run);
    free(pass);
    if (rc != CLI_OK) {
        cli_run_free(&run);
        return rc;
    }
    const dyn_model *m = run.model;
    cont_settings s;
    memset(&s, 0, sizeof s);
    int ip = -1, ip2 = -1, iy = 0;
    rc = param_arg(m, "--par", a.par, &ip);
    if (rc == CLI_OK && a.par2)
        rc = param_arg(m, "--par2", a.par2, &ip2);
    if (rc == CLI_OK && ip2 == ip)
        rc = cli_usage_error("continue", "--par2 %s: give another parameter than --par", a.par2);
    if (rc == CLI_OK && (cli_param_is_size(m, a.par) || (a.par2 && cli_param_is_size(m, a.par2))))
        rc = cli_usage_error("continue", "the size of %s cannot be continued in", m->name);
    if (rc == CLI_OK && a.ynam && (iy = dyn_model_state_index(m, a.ynam)) < 0)
        rc = cli_usage_error("continue", "--y '%s': not a state of %s", a.ynam, m->name);
    if (rc == CLI_OK) {
        dyn_cont_opts_default(&s.opts, ip);
        s.opts.ip2 = ip2;
        s.opts.t = run.t0;
        s.opts.map = dyn_method_is_map(run.method);
        s.opts.map_period = s.opts.map && run.every > 1 ? (int)fmin(run.every, 1e6) : 1;
        rc = settings(&a, run.par, m, &s);
    }
    if (rc == CLI_OK && !a.ynam && s.autovar[0] &&
        (iy = dyn_model_state_index(m, s.autovar)) < 0)
        rc = cli_usage_error("continue", "%s: autovar=%s: not a state of %s (AUTOVAR names the "
                             "state on the diagram's y axis)", s.autovar_from, s.autovar,
                             m->name);
    if (rc == CLI_OK && a.scheme_text)
        rc = parse_scheme(a.scheme_text, &s.opts.jac);
    double *at = NULL;
    long n_at = 0;
    if (rc == CLI_OK && a.at) {
        const char *eq = strchr(a.at, '=');
        if (!eq || (size_t)(eq - a.at) != strlen(a.par) || strncmp(a.at, a.par, strlen(a.par)))
            rc = cli_usage_error("continue", "--at '%s': give %s=V1,V2,... (the --par "
                                 "parameter's values)", a.at, a.par);
        else
            rc = cli_parse_values("continue", a.at, eq + 1, CONT_MAX_AT, &at, &n_at);
        s.opts.at = at;
        s.opts.n_at = (int)n_at;
    }
    /* periodic orbits from the Hopf points, by collocation (dynkit/colloc.h) */
    s.opts.periodic = dyn_po_continue_hopf;
    s.opts.periodic_ctx = (void *)cli_eig_solver();
    s.opts.orbits = wants_page(&a);
    dyn_diagram d;
    memset(&d, 0, sizeof d);
    cli_progress progress;
    cli_progress_start(&progress, 0);
    const continue_progress_ctx pc = {m, &progress};
    d.progress = continue_progress;
    d.progress_ctx = (void *)&pc;
    dyn_cont_info info;
    memset(&info, 0, sizeof info);
    int steady = 0;
    if (rc == CLI_OK) {
        const cont_steady_args sa = {a.unknown, a.cyclic, a.init, a.n_init};
        rc = cont_steady_run(argv[0], &run, &sa, &s.opts, &d, &info, &steady);
        if (rc == CLI_OK && steady && info.message[0])
            fprintf(stderr, "dynkit: note: %s\n", info.message);
    }
    if (rc == CLI_OK && !steady && (a.unknown || a.cyclic))
        rc = cli_usage_error("continue", "--unknown and --cyclic are for a mechanism file's "
                                         "steady motions (FILE.mech)");
    if (rc == CLI_OK && !steady)
        rc = cli_kinds_refuse_markov("continue", m, "a branch of its equilibria");
    if (rc == CLI_OK && !steady) {
        cli_kinds_noise_note("continue", m, NULL);
        int st = dyn_continue(m, run.par, run.y0, &s.opts, &d, &info);
        if (st && info.start_failed)
            st = start_from_run(&run, &s.opts, &d, &info, &progress);
        if (st && info.start_failed && s.opts.map_period <= 1)
            st = start_from_equilibria(&run, &s.opts, &d, &info, &progress);
        cli_progress_finish(&progress); /* the line cleared before the messages */
        if (st) {
            cli_error("continue: %s", info.message);
            rc = CLI_FAILED;
        } else if (info.message[0]) {
            cli_stderr("dynkit: note: %s\n", info.message);
        }
    }
    cli_progress_finish(&progress);
    if (rc == CLI_OK) {
        const cont_view v = {m, run.par, &d, &s, iy};
        rc = cont_write_outputs(&v, a.output, a.json, a.svg, a.html);
    }
    dyn_diagram_free(&d);
    free(at);
    cli_run_free(&run);
    return rc;
}
