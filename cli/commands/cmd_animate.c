/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit animate MODEL: a run (and --compare runs) as a self-contained HTML page that plays
 * the motion (plane, cart, pendulum, van der Pol, a mechanism file from its geometry:
 * mech_page.c) and the time series of every state.
 * Without --output the page goes to MODEL.html in the current directory (MODEL-2.html, ...
 * when that exists: a file is never replaced unasked), and the tool says where. */
#include <ctype.h>
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/cart.h"
#include "commands/animate_homework.h"
#include "dynkit/mbs.h"
#include "util/out_file.h"
#include "pages/pages.h"

static void animate_help(void)
{
    puts("Usage: dynkit animate MODEL [run options] [--compare METHOD[:STEP]]...\n"
         "                      [--output FILE.html]\n"
         "\n"
         "Run MODEL and write one self-contained HTML page (no network, everything inline) that\n"
         "plays the run in real time: the plane in 3D\n"
         "(drag to rotate, wheel to zoom), the cart from above with the track of its wheels,\n"
         "the pendulum, the phase plane of van der Pol, a mechanism file NAME.mech from its\n"
         "geometry (in 3D, or in 2D when it moves in a plane), and for every model the time\n"
         "series of its states and outputs with a moving cursor. The cart without run options\n"
         "plays the homework's run (problem 4: the forward run on the force table of the\n"
         "prescribed path, and that path).\n"
         "\n"
         "  --compare M[:H]      overlay a run with method M (and step H; default the run's\n"
         "                       step), repeatable: --compare euler --compare rk4:0.001\n"
         "  -o, --output FILE    the page's file; without it MODEL.html in the current\n"
         "                       directory (MODEL-2.html, ... when that exists; never replaced\n"
         "                       unasked), and the file written is named on stderr;\n"
         "                       '-' writes the page to standard output\n"
         "  --ani FILE.ani       play XPPAUT's animation FILE.ani above the plots; a model\n"
         "                       file NAME.ode (or .mech, .c) plays NAME.ani beside it without\n"
         "                       this option, when there is one (beside .mech or .c only when\n"
         "                       it fits that model and no NAME.ode is there: else a warning)\n"
         "  --no-ani             leave out the model file's NAME.ani\n"
         "  --live               a live page: the model compiled to WebAssembly runs in the\n"
         "                       page, with a slider and a box for every parameter and\n"
         "                       initial value, the method, step, tolerances and span; it\n"
         "                       reruns on every change, a click in a phase plane starts a\n"
         "                       trajectory there, and it shows the command line of the run\n"
         "                       and a CSV download (needs clang with wasm32-wasi at build\n"
         "                       and page time: " "clang lld wasi-libc libclang-rt-14-dev-wasm32;\n"
         "                       without them the page is static and says why)\n"
         "A long run is thinned to at most 2000 samples (first and last kept).\n"
         "Controls: play/pause, speed 0.1x-10x, time slider; keys: space play/pause,\n"
         "left/right one sample, shift+left/right 1 s, up/down speed, home/end.\n"
         "\n"
         "Examples:\n"
         "  dynkit animate plane --compare euler --output plane.html\n"
         "  dynkit animate cart --output cart.html\n"
         "  dynkit animate vanderpol --compare euler:0.05 --compare heun --output vdp.html\n"
         "  dynkit animate examples/models/double_pendulum.ode --output dp.html   # + .ani\n"
         "  dynkit animate examples/mechanisms/top.mech --output top.html\n"
         "  dynkit animate vanderpol --live --output vdp-live.html\n");
    cli_view_options_help(stdout);
}

typedef struct animate_page {
    const cli_view *v;
    const cli_ani *ani;
    const dyn_mech_scene *mech;
    int homework; /* the homework's run (animate_homework.c) */
    const cli_live *live; /* the model in WebAssembly (--live), or NULL */
    const char *spec;     /* MODEL as given */
} animate_page;

/* What the run shows when the model has inputs and no --forces table was given: the inputs
 * held at the parameters of their names (the cart's Fx = -50 N), which is not a homework's
 * run; said on the page, with the command of the homework's run for the cart. */
static void write_shows(cli_json *j, const cli_run *run, int homework)
{
    const dyn_model *m = run->model;
    char text[768];
    if (homework) {
        cli_animate_homework_shows(text, sizeof text);
        cli_json_key(j, "shows");
        cli_json_string(j, text);
        return;
    }
    if (m->n_inputs <= 0 || run->forces_path)
        return;
    size_t n = (size_t)snprintf(text, sizeof text,
                                "Shown: a run with the inputs held constant, as no --forces "
                                "table was given");
    for (int i = 0; i < m->n_inputs && n < sizeof text; i++) {
        const int k = dyn_model_param_index(m, m->inputs[i].name);
        if (k < 0)
            continue;
        const char *unit = m->inputs[i].unit ? m->inputs[i].unit : "";
        n += (size_t)snprintf(text + n, sizeof text - n, "%s %s = %s%s%s", i ? "," : ":",
                              m->inputs[i].name, CLI_NUM(dyn_model_get_param(m, run->par, k)),
                              *unit ? " " : "", unit);
    }
    if (n < sizeof text && m == &dyn_model_cart)
        snprintf(text + n, sizeof text - n,
                 ". dynkit animate cart without run options plays the homework's run "
                 "(problem 4).");
    else if (n < sizeof text)
        snprintf(text + n, sizeof text - n, ".");
    cli_json_key(j, "shows");
    cli_json_string(j, text);
}

static int page_data(cli_json *j, void *ctx)
{
    const animate_page *pg = ctx;
    const cli_view *v = pg->v;
    cli_json_begin_object(j);
    cli_json_animate_runs(j, v);
    write_shows(j, &v->run, pg->homework);
    int bad = 0;
    if (pg->ani && pg->ani->ani) {
        cli_json_key(j, "ani");
        bad = cli_json_ani(j, pg->ani, v);
    }
    if (pg->mech && !bad) {
        cli_json_key(j, "mech");
        bad = cli_json_mech(j, pg->mech, v);
    }
    if (pg->mech && pg->live && pg->live->module && pg->live->scene_inputs && !bad) {
        cli_json_key(j, "mech_plan");
        cli_json_mech_plan(j, pg->mech);
    }
    if (pg->live && pg->live->module && !bad) {
        cli_json_key(j, "live");
        bad = cli_json_live(j, pg->live, v, pg->spec);
    }
    cli_json_end_object(j);
    return bad || j->bad;
}

/* Open MODEL.html (or MODEL-2.html, ... up to MODEL-99.html) in the current directory,
 * never replacing a file (C11's exclusive "wx" mode); the name into path. */
static FILE *open_default(const char *model, char *path, size_t size)
{
    char base[64];
    size_t n = 0;
    for (const char *p = model; *p && n + 1 < sizeof base; p++)
        base[n++] = isalnum((unsigned char)*p) || *p == '-' || *p == '_' ? *p : '_';
    base[n] = '\0';
    for (int k = 1; k < 100; k++) {
        if (k == 1)
            snprintf(path, size, "%s.html", n ? base : "animation");
        else
            snprintf(path, size, "%s-%d.html", n ? base : "animation", k);
        FILE *f = fopen(path, "wx");
        if (f || errno != EEXIST)
            return f;
    }
    return NULL;
}

int cli_cmd_animate(int argc, char **argv)
{
    for (int i = 0; i < argc; i++)
        if (cli_is_help(argv[i])) {
            animate_help();
            return CLI_OK;
        }
    /* --no-ani is a flag: taken out before the run options are read */
    char **args = calloc((size_t)argc + 1, sizeof *args);
    if (!args) {
        cli_error("out of memory");
        return CLI_FAILED;
    }
    int n_args = 0, no_ani = 0, live_asked = 0;
    for (int i = 0; i < argc; i++) {
        if (i > 0 && cli_flag(argv[i], "no-ani"))
            no_ani = 1;
        else if (i > 0 && cli_flag(argv[i], "live"))
            live_asked = 1;
        else
            args[n_args++] = argv[i];
    }
    static const char *const extra[] = {"ani", NULL};
    const char *extra_values[1] = {NULL};
    cli_view v;
    cli_ani ani;
    memset(&ani, 0, sizeof ani);
    int rc = cli_view_parse("animate", n_args, args, extra, extra_values, &v);
    /* the page plays the run: a Poincaré section is drawn by dynkit plot --section */
    if (rc == CLI_OK && v.run.section_given && v.run.section.kind != DYN_POINCARE_NONE)
        rc = cli_usage_error("animate", "--section is not accepted here: the page plays the "
                                        "run (dynkit plot --section draws the crossings)");
    if (rc == CLI_OK)
        v.run.section.kind = DYN_POINCARE_NONE; /* a model file's @ poimap is run's */
    /* a live page reruns the model with constant inputs: not the homework's table */
    const int homework =
        rc == CLI_OK && !live_asked && cli_animate_homework_applies(&v, n_args, args);
    if (rc == CLI_OK && no_ani && extra_values[0])
        rc = cli_usage_error("animate", "--ani and --no-ani contradict each other");
    /* the animation is read before the runs: an error in it writes nothing */
    if (rc == CLI_OK && !no_ani)
        rc = cli_ani_open("animate", args[0], extra_values[0], v.run.model, &ani);
    dyn_mech_scene *mech = NULL;
    if (rc == CLI_OK)
        rc = cli_mech_scene_open(args[0], v.run.model, &mech);
    free(args);
    static const char *const html[] = {".html", ".htm", NULL};
    if (rc == CLI_OK)
        rc = cli_out_check_extension("animate", "--output", v.run.output_path, html);
    if (homework)
        rc = cli_animate_homework_setup(&v);
    int run_rc = rc == CLI_OK ? cli_view_record(&v) : rc;
    cli_live live;
    memset(&live, 0, sizeof live);
    if (rc == CLI_OK && live_asked &&
        (ani.ani ? cli_live_build_ani(v.run.model, ani.path, &live) /* an .ode's or a .mech's */
                 : cli_live_build(v.run.model, &live)) != 0)
        cli_warning("the page is not live, it shows the run it was written with: %s", live.why);
    if (homework && run_rc != CLI_USAGE && cli_animate_homework_finish(&v) != CLI_OK)
        rc = CLI_FAILED;
    if (rc == CLI_OK && (run_rc == CLI_USAGE || v.n_series == 0))
        rc = run_rc;
    FILE *out = stdout;
    cli_out outf = {0};
    char default_path[128] = "";
    const char *path = v.run.output_path;
    if (rc == CLI_OK && !path && !(out = open_default(v.run.model->name, default_path,
                                                     sizeof default_path))) {
        rc = cli_usage_error("animate", "cannot write %s in the current directory: %s (give "
                                        "--output FILE.html)",
                             default_path, strerror(errno));
        out = stdout;
    } else if (rc == CLI_OK && path) {
        /* a named --output: a temporary file renamed over it at the end (out_file.h) */
        rc = cli_out_open(&outf, "--output", path);
        out = rc == CLI_OK ? outf.f : stdout;
    }
    if (rc == CLI_OK) {
        char title[160];
        snprintf(title, sizeof title, "dynkit animate %s", v.run.model->name);
        animate_page pg = {&v, &ani, mech, homework, &live, argv[0]};
        cli_html_page_allow_wasm(live.module != NULL);
        rc = cli_html_page_write(out, title, "animate.html", page_data, &pg);
        cli_html_page_allow_wasm(0);
        if (path) {
            /* the page of a run that failed part-way is kept: it shows what was computed */
            int close_rc = cli_out_close(&outf, rc == CLI_OK);
            if (rc == CLI_OK)
                rc = close_rc;
            out = stdout;
        }
        if (rc == CLI_OK && run_rc != CLI_OK)
            rc = run_rc;
    }
    if (out != stdout) { /* MODEL.html: a cut page is removed, never announced */
        errno = 0;
        const int cut = ferror(out) != 0;
        if ((fclose(out) != 0 || cut) && default_path[0]) {
            cli_error("writing %s failed: %s; the file is removed", default_path,
                      errno ? strerror(errno) : "a write failed");
            remove(default_path);
            default_path[0] = '\0';
            rc = CLI_FAILED;
        }
    }
    if (default_path[0] && (rc == CLI_OK || rc == CLI_FAILED))
        cli_stderr("dynkit: wrote %s (open it in a browser; --output FILE names the file, "
                   "--output - writes to standard output)\n",
                   default_path);
    cli_live_free(&live);
    cli_ani_free(&ani);
    dyn_mech_scene_free(mech);
    cli_view_free(&v);
    return rc;
}
