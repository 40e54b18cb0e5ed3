/* libFuzzer harness of the command line's number parsers (cli/util/args.c: cli_parse_number with
 * pi, degrees and a divisor, cli_parse_count) and of the option values built on them
 * (cli/run/run_values.c: --tspan, --rtol lists, --times lists and the @FILE reader). An input
 * that starts with '@' is the content of a --times file; any other is one argument. Accepted
 * values must be finite and ordered as promised; nothing may crash, leak or read out of
 * bounds (built with -fsanitize=fuzzer,address,undefined; see fuzz/CMakeLists.txt).
 *   fuzz_number -max_total_time=300 -dict=fuzz/number.dict fuzz/corpus/number */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "run/run_parse.h"

/* run_values.c's --set/--init and --event need a model; none is reached from here */
int dyn_model_param_index(const dyn_model *m, const char *name)
{
    (void)m, (void)name;
    abort();
}
int dyn_model_state_index(const dyn_model *m, const char *name)
{
    (void)m, (void)name;
    abort();
}
void dyn_model_set_param(const dyn_model *m, void *par, int i, double value)
{
    (void)m, (void)par, (void)i, (void)value;
    abort();
}
double dyn_model_get_param(const dyn_model *m, const void *par, int i)
{
    (void)m, (void)par, (void)i;
    abort();
}
int cli_param_is_size(const dyn_model *m, const char *name)
{
    (void)m, (void)name;
    abort();
}

/* the tool records the files a command reads (cli/util/out_file.c) so that no output
 * replaces one; the harness writes nothing */
void cli_input_note(const char *path, const char *what)
{
    (void)path, (void)what;
}

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static char times_path[64];

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc, (void)argv;
    /* the usage errors of rejected values go nowhere (libFuzzer and the sanitizers keep
     * their own handle of the standard error) */
    FILE *null = fopen("/dev/null", "w");
    if (null)
        stderr = null;
    snprintf(times_path, sizeof times_path, "/tmp/fuzz_number_%ld.times", (long)getpid());
    return 0;
}

static void check_times(const cli_run *run, int rc)
{
    if (rc == CLI_OK) {
        if (run->n_times < 1 || !run->times)
            abort();
        for (long k = 0; k < run->n_times; k++)
            if (!isfinite(run->times[k]) || (k > 0 && run->times[k] < run->times[k - 1]))
                abort();
    } else if (rc != CLI_USAGE && rc != CLI_FAILED) {
        abort();
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    cli_run run;
    memset(&run, 0, sizeof run);
    if (size > 0 && data[0] == '@') {
        FILE *f = fopen(times_path, "wb");
        if (!f)
            return 0;
        fwrite(data + 1, 1, size - 1, f);
        fclose(f);
        char arg[80];
        snprintf(arg, sizeof arg, "@%s", times_path);
        check_times(&run, cli_parse_times("run", arg, &run));
        free(run.times);
        remove(times_path);
        return 0;
    }
    char *text = malloc(size + 1);
    if (!text)
        return 0;
    memcpy(text, data, size);
    text[size] = '\0';

    double v = 0.0;
    if (cli_parse_number(text, &v) == 0 && !isfinite(v))
        abort();
    long count = -1;
    if (cli_parse_count(text, 0, &count) == 0 && count < 0)
        abort();
    double t0 = 0.0, t1 = 0.0;
    if (cli_parse_tspan("run", text, &t0, &t1) == CLI_OK &&
        !(isfinite(t0) && isfinite(t1) && t1 > t0))
        abort();
    double scalar = 0.0, *vec = NULL;
    if (cli_parse_tolerance("run", "--rtol", text, 3, &scalar, &vec) == CLI_OK) {
        if (vec) {
            for (int i = 0; i < 3; i++)
                if (!(vec[i] >= 0) || !isfinite(vec[i]))
                    abort();
        } else if (!(scalar > 0) || !isfinite(scalar)) {
            abort();
        }
    }
    free(vec);
    if (text[0] != '@') {
        check_times(&run, cli_parse_times("run", text, &run));
        free(run.times);
    }
    free(text);
    return 0;
}
