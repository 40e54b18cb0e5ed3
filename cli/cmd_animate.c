/* dynkit animate MODEL: a run (and --compare runs) as a self-contained HTML page that plays
 * the motion (plane, cart, pendulum, van der Pol) and the time series of every state. */
#include <errno.h>
#include <string.h>

#include "pages.h"

static void animate_help(void)
{
    puts("Usage: dynkit animate MODEL [run options] [--compare METHOD[:STEP]]...\n"
         "                      [--output FILE.html]\n"
         "\n"
         "Run MODEL and write one self-contained HTML page (no network, everything inline;\n"
         "standard output without --output) that plays the run in real time: the plane in 3D\n"
         "(drag to rotate, wheel to zoom), the cart from above with the track of its wheels,\n"
         "the pendulum, the phase plane of van der Pol, and for every model the time series\n"
         "of its states and outputs with a moving cursor.\n"
         "\n"
         "  --compare M[:H]      overlay a run with method M (and step H; default the run's\n"
         "                       step), repeatable: --compare euler --compare rk4:0.001\n"
         "A long run is thinned to at most 2000 samples (first and last kept).\n"
         "Controls: play/pause, speed 0.1x-10x, time slider; keys: space play/pause,\n"
         "left/right one sample, shift+left/right 1 s, up/down speed, home/end.\n"
         "\n"
         "Examples:\n"
         "  dynkit animate plane --compare euler --output plane.html\n"
         "  dynkit animate cart --output cart.html\n"
         "  dynkit animate vanderpol --compare euler:0.05 --compare heun --output vdp.html\n");
    cli_run_options_help(stdout);
}

static int page_data(cli_json *j, void *ctx)
{
    const cli_view *v = ctx;
    cli_json_begin_object(j);
    cli_json_key(j, "kind");
    cli_json_string(j, "animate");
    cli_json_key(j, "model");
    cli_json_model(j, v->run.model, v->run.par);
    cli_json_key(j, "span");
    const double span[2] = {v->run.t0, v->run.t1};
    cli_json_numbers(j, span, 2, 1);
    cli_json_key(j, "runs");
    cli_json_begin_array(j);
    for (int k = 0; k < v->n_series; k++)
        cli_json_series(j, v->run.model, &v->series[k]);
    cli_json_end_array(j);
    cli_json_end_object(j);
    return j->bad;
}

int cli_cmd_animate(int argc, char **argv)
{
    for (int i = 0; i < argc; i++)
        if (cli_is_help(argv[i])) {
            animate_help();
            return CLI_OK;
        }
    cli_view v;
    int rc = cli_view_parse("animate", argc, argv, NULL, NULL, &v);
    int run_rc = rc == CLI_OK ? cli_view_record(&v) : rc;
    if (rc == CLI_OK && (run_rc == CLI_USAGE || v.n_series == 0))
        rc = run_rc;
    FILE *out = stdout;
    if (rc == CLI_OK && v.run.output_path && !(out = fopen(v.run.output_path, "w"))) {
        rc = cli_usage_error("animate", "cannot open --output '%s' for writing: %s",
                             v.run.output_path, strerror(errno));
        out = stdout;
    }
    if (rc == CLI_OK) {
        char title[160];
        snprintf(title, sizeof title, "dynkit animate %s", v.run.model->name);
        rc = cli_html_page_write(out, title, "animate.html", page_data, &v);
        if (rc == CLI_OK && run_rc != CLI_OK)
            rc = run_rc;
    }
    if (out != stdout)
        fclose(out);
    cli_view_free(&v);
    return rc;
}
