/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit inverse cart (FILE.mech: inverse_mech.c): the inverse dynamics of homework problem 4a/4b. Writes the force
 * table t,Fx,Fy of the prescribed backward motion sX = -v0 t, theta = (pi/8) sin(2 pi f t)
 * (dyn_cart_force_table) and prints on stderr the initial state that goes with it, as
 * options for 'dynkit run cart --forces', and the final forces.
 */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "util/escape.h"
#include "commands/inverse_mech.h"
#include "util/out_file.h"
#include "tables/table_formats.h"

static void inverse_help(void)
{
    puts("Usage: dynkit inverse cart [options]\n"
         "       dynkit inverse FILE.mech [--prescribe COORD=FORMULA]... [--inputs A,B,...]\n"
         "                                [run options]\n"
         "\n"
         "FILE.mech: the forces of the mechanism's prescribed motions (its 'prescribe' lines and\n"
         "each --prescribe COORD=FORMULA, a formula of t, read as 'prescribe Q_COORD: COORD =\n"
         "FORMULA'). The mechanism runs from its initial state moved onto the constraints (the\n"
         "changes are printed, as 'run --project-init' does) with the run options (--method,\n"
         "--tspan, --step, --rtol, --atol, --set, --init, -o FILE, --quiet); the table has t, the\n"
         "generalized forces that drive the prescribed coordinates, then the other constraints'\n"
         "forces. --inputs A,B,...: instead of those generalized forces, the values of these\n"
         "parameters (one per prescribed motion, e.g. the inputs of the file) that drive the\n"
         "motion, found at each sample; 'dynkit run FILE.mech --forces' reads that table.\n"
         "Example (problem 4a with examples/mechanisms/cart.mech):\n"
         "  dynkit inverse examples/mechanisms/cart.mech --prescribe sX=-20*t \\\n"
         "      --prescribe 'theta=pi/8*sin(4*pi*t)' --inputs Fx,Fy --tspan 0:4.99 --step 0.01\n"
         "\n"
         "cart:\n"
         "Inverse dynamics of the cart (homework problem 4a, 4b): the body-frame forces Fx, Fy\n"
         "at the front wheel that make the cart follow sX = -v0 t, theta = (pi/8) sin(2 pi f t)\n"
         "(sY follows from the no-slip constraint of the rear axle, with sY(0) = 0), at the N\n"
         "sample times t_k = k Ts. Writes the table as CSV (header t,Fx,Fy; each number the\n"
         "shortest decimal that reads back to the same double) and prints on standard error the "
         "initial state of the motion as --init options, the\n"
         "final forces, and the command of the forward run (problem 4c).\n"
         "\n"
         "Options:\n"
         "  --set v0=V           backward speed in m/s (default 20)\n"
         "  --set f=F            frequency of the heading oscillation in Hz (default 2)\n"
         "  --set N=COUNT        number of samples (default 500)\n"
         "  --set Ts=H           sample time in s (default 0.01)\n"
         "  --set NAME=VALUE     a cart parameter: m, length_cart, width_cart, ... (see\n"
         "                       'dynkit info cart'); give the same --set to the forward run.\n"
         "                       Each VALUE is a number or a formula of the cart's\n"
         "                       parameters, as run --set takes it (--set v0=2*g): the\n"
         "                       numbers are set first, then the formulas in their order\n"
         "  -o, --output FILE    write the table to FILE instead of standard output ('-'), in\n"
         "                       the format of its extension: .csv, .json, .npy, .npz, .mat\n"
         "                       ('dynkit run --forces' reads CSV)\n"
         "  --quiet              print nothing on standard error\n"
         "\n"
         "Example (problem 4): write the table, then drive the cart with it (modified Euler at\n"
         "the table's sample time and span, nearest sample of the table):\n"
         "  dynkit inverse cart --output forces.csv\n"
         "  dynkit run cart --forces forces.csv --method heun --outputs \\\n"
         "      --init sX=0 --init sY=0 --init theta=0 --init dsX=-20 \\\n"
         "      --init dsY=4.934802200544679 --init omega=4.934802200544679\n"
         "\n"
         "Exit status: 0 success, 1 the output could not be written, 2 bad command line.");
}

/* Print the --set options of parameters that differ from their defaults. */
static void print_changed_params(FILE *out, const dyn_model *m, const void *par)
{
    for (int i = 0; i < m->n_params; i++) {
        double v = dyn_model_get_param(m, par, i);
        if (v != m->params[i].value)
            fprintf(out, " --set %s=%s", m->params[i].name, CLI_NUM(v));
    }
}

/* What the inverse dynamics of the cart take besides the cart's parameters. */
typedef struct inverse_settings {
    double v0, f, Ts, N;
} inverse_settings;

/* 1 when the VALUE of NAME=VALUE is a number (not a formula) */
static int is_number_assignment(const char *text)
{
    const char *eq = strchr(text, '=');
    double v;
    return eq && cli_parse_number(eq + 1, &v) == 0;
}

/* One --set NAME=VALUE, VALUE a number or a formula of the cart's parameters. */
static int apply_set(const char *text, const dyn_model *m, dyn_cart_par *par, inverse_settings *set)
{
    const char *eq = strchr(text, '=');
    char name[64], why[400] = "";
    double value;
    if (!eq || eq == text || (size_t)(eq - text) >= sizeof name ||
        cli_parse_value(eq + 1, &value, why, sizeof why))
        return cli_usage_error("inverse",
                               "--set '%s' is not accepted%s%s: give NAME=VALUE, VALUE a finite "
                               "number or a formula of the cart's parameters (2*pi/3, v0=2*g)",
                               text, why[0] ? ": " : "", why);
    memcpy(name, text, (size_t)(eq - text));
    name[eq - text] = '\0';
    int k;
    if (strcmp(name, "v0") == 0)
        set->v0 = value;
    else if (strcmp(name, "f") == 0)
        set->f = value;
    else if (strcmp(name, "Ts") == 0)
        set->Ts = value;
    else if (strcmp(name, "N") == 0)
        set->N = value;
    else if ((k = dyn_model_param_index(m, name)) >= 0)
        dyn_model_set_param(m, par, k, value);
    else
        return cli_usage_error("inverse",
                               "--set: unknown name '%s' (accepted: v0, f, N, Ts, m, "
                               "length_cart, width_cart, Fx, Fy, mu, g)",
                               name);
    return CLI_OK;
}

int cli_cmd_inverse(int argc, char **argv)
{
    const dyn_model *m = &dyn_model_cart;
    char err[256];
    for (int i = 0; i < argc; i++)
        if (cli_is_help(argv[i])) {
            inverse_help();
            return CLI_OK;
        }
    if (argc < 1 || argv[0][0] == '-')
        return cli_usage_error("inverse", "missing MODEL (accepted: cart, or a mechanism file "
                               "NAME.mech)");
    if (cli_has_extension(argv[0], ".mech"))
        return cli_inverse_mech(argc, argv);
    if (strcmp(argv[0], "cart") != 0)
        return cli_usage_error("inverse", "no inverse dynamics for model '%s' (accepted: cart, "
                               "or a mechanism file NAME.mech)", argv[0]);
    dyn_cart_par par;
    dyn_model_default_params(m, &par, err, sizeof err);
    inverse_settings set = {20.0, 2.0, 0.01, 500.0};
    const char *output_path = NULL;
    int quiet = 0, n_sets = 0;
    const char **sets = malloc((size_t)argc * sizeof *sets);
    if (!sets) {
        cli_error("out of memory");
        return CLI_FAILED;
    }
    for (int i = 1; i < argc; i++) {
        const char *v = NULL;
        int r;
        if ((r = cli_option(argc, argv, &i, "set", &v)) != 0) {
            if (r < 0) {
                free(sets);
                return cli_usage_error("inverse", "option --set needs a value");
            }
            sets[n_sets++] = v;
        } else if ((r = cli_option(argc, argv, &i, "output", &v)) != 0) {
            if (r < 0) {
                free(sets);
                return cli_usage_error("inverse", "option --output needs a value");
            }
            output_path = v;
        } else if (cli_flag(argv[i], "quiet")) {
            quiet = 1;
        } else {
            static const char *const options[] = {"--set", "--output", "--quiet"};
            free(sets);
            return cli_unknown_option("inverse", argv[i], options, 3);
        }
    }
    /* the numbers first, then the formulas of the cart's parameters set so far, as run
     * takes --set (docs/cli.md, "Numbers") */
    cli_formula_params(m, &par);
    int rc = CLI_OK;
    for (int pass = 0; pass < 2; pass++)
        for (int k = 0; k < n_sets && rc == CLI_OK; k++)
            if (is_number_assignment(sets[k]) == (pass == 0))
                rc = apply_set(sets[k], m, &par, &set);
    cli_formula_params(NULL, NULL);
    free(sets);
    if (rc != CLI_OK)
        return rc;
    double v0 = set.v0, f = set.f, Ts = set.Ts, N_value = set.N;
    if (!(N_value >= 1.0 && N_value <= 1e8 && N_value == floor(N_value)))
        return cli_usage_error("inverse",
                               "--set N=%g is not accepted: give a whole number of samples "
                               "from 1 to 1e8",
                               N_value);
    if (!(Ts > 0.0))
        return cli_usage_error("inverse", "--set Ts=%g is not accepted: give a sample time > 0",
                               Ts);
    if (!(f >= 0.0))
        return cli_usage_error("inverse", "--set f=%g is not accepted: give a frequency >= 0",
                               f);
    if (dyn_cart_prepare(&par, err, sizeof err))
        return cli_usage_error("inverse", "%s", err);
    cli_format format;
    char ferr[512] = "";
    if (cli_format_of_path(output_path ? output_path : "-", &format, ferr, sizeof ferr))
        return cli_usage_error("inverse", "--output %s", ferr);
    const long N = (long)N_value;
    double *table = malloc((size_t)N * 3 * sizeof *table);
    if (!table) {
        cli_error("out of memory");
        return CLI_FAILED;
    }
    if (dyn_cart_force_table(&par, v0, f, N, Ts, table, err, sizeof err)) {
        free(table);
        return cli_usage_error("inverse", "%s", err);
    }
    double y0[6];
    dyn_cart_prescribed(&par, v0, f, 0.0, y0, NULL);
    if (output_path && strcmp(output_path, "-") == 0)
        output_path = NULL;
    /* written beside the file and renamed when complete: a failure keeps the old file */
    cli_out outf;
    const int open_rc = cli_out_open(&outf, "--output", output_path);
    if (open_rc != CLI_OK) {
        free(table);
        return open_rc;
    }
    FILE *out = outf.f;
    const char *names[3] = {"t", m->inputs[0].name, m->inputs[1].name};
    const char *units[3] = {"s", m->inputs[0].unit, m->inputs[1].unit};
    const cli_table_info info = {.model = m->name,
                                 .step = Ts,
                                 .rtol = NAN,
                                 .atol = NAN,
                                 .t0 = 0.0,
                                 .t1 = (double)(N - 1) * Ts,
                                 .cols = 3,
                                 .n_y = 2,
                                 .y_name = "forces",
                                 .names = names,
                                 .units = units};
    cli_table *tab = cli_table_open(out, format, &info, ferr, sizeof ferr);
    int bad = !tab;
    for (long k = 0; k < N && !bad; k++)
        bad = cli_table_row(tab, table[3 * k], table + 3 * k + 1, 2, NULL, 0) != 0;
    bad |= tab && cli_table_finish(tab, ferr, sizeof ferr) != 0;
    cli_table_free(tab);
    bad |= fflush(out) != 0 || ferror(out);
    if (out != stdout)
        bad |= cli_out_close(&outf, !bad) != CLI_OK;
    else
        clearerr(stdout); /* reported below, not again at exit */
    rc = CLI_OK;
    if (bad) {
        cli_error("writing the force table failed: %s",
                ferr[0] ? ferr : strerror(errno));
        rc = CLI_FAILED;
    } else if (!quiet) {
        const double *last = table + 3 * (N - 1);
        cli_stderr("dynkit: cart inverse dynamics: sX = -v0 t, theta = (pi/8) sin(2 pi f t), "
                   "v0 = %g m/s, f = %g Hz;\n"
                   "dynkit: %ld samples at Ts = %g s, te = (N-1) Ts = %s s\n",
                   v0, f, N, Ts, CLI_NUM(last[0]));
        cli_stderr("dynkit: initial state (dsY from the constraint, %s m/s):\n ", CLI_NUM(y0[4]));
        for (int i = 0; i < 6; i++)
            cli_stderr(" --init %s=%s", m->states[i].name, CLI_NUM(y0[i]));
        cli_stderr("\ndynkit: final forces at te = %s s: Fx = %s N, Fy = %s N\n", CLI_NUM(last[0]),
                   CLI_NUM(last[1]), CLI_NUM(last[2]));
        char shown[4 * 4096 + 1];
        cli_stderr("dynkit: forward run (problem 4c): dynkit run cart --forces %s "
                   "--method heun",
                   output_path ? cli_terminal_text(output_path, 0, shown, sizeof shown) : "FILE");
        print_changed_params(stderr, m, &par);
        for (int i = 0; i < 6; i++)
            cli_stderr(" --init %s=%s", m->states[i].name, CLI_NUM(y0[i]));
        fputc('\n', stderr);
    }
    free(table);
    return rc;
}
