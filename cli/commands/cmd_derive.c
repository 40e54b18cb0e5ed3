/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit derive FILE.mech: what the mechanism front end derives (dyn_mech_derive_text), the
 * mass matrix, the forces and the constraints' rows as formulas in the file's names. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "dynkit/mbs.h"
#include "util/out_file.h"

static void derive_help(void)
{
    puts("Usage: dynkit derive FILE.mech [--c FILE.c]\n\n"
         "Print the equations of motion that dynkit derives from a mechanism file by TMT\n"
         "(docs/mechanisms.md): M q'' = F + D' lambda with the constraints D q'' + c = 0, as\n"
         "formulas of the coordinates q, their speeds, t and the parameters: each entry\n"
         "M[a,b] of the mass matrix's lower triangle, each force F[a], and for each\n"
         "constraint its row D[name,a] and convective term c[name]; then the file's fixed\n"
         "quantities they use. The formulas are in the file's operators (^ is a power).\n"
         "With speeds u declared by a speeds line, the kinematic equations q' = W(q) u\n"
         "come first and M u' = F + D' lambda is written for the speeds.\n\n"
         "Options:\n"
         "  --c FILE.c           write the model as C instead (the text dynkit compiles): a\n"
         "                       model of its own, 'dynkit run FILE.c' runs it");
}

int cli_cmd_derive(int argc, char **argv)
{
    if (argc >= 1 && cli_is_help(argv[0])) {
        derive_help();
        return CLI_OK;
    }
    const char *c_path = NULL;
    if (argc == 3 && strcmp(argv[1], "--c") == 0)
        c_path = argv[2];
    else if (argc != 1)
        return cli_usage_error("derive", argc ? "expected FILE.mech [--c FILE.c], got %d arguments"
                                              : "expected a mechanism file FILE.mech",
                               argc);
    const char *path = argv[0];
    const size_t n = strlen(path);
    if (n < 5 || strcmp(path + n - 5, ".mech") != 0)
        return cli_usage_error("derive", "'%s' is not a mechanism file FILE.mech", path);
    size_t len = 0;
    char *text = cli_read_model_file(path, &len);
    if (!text)
        return CLI_USAGE;
    char *out = NULL;
    dyn_lang_diag diag;
    const int rc = c_path ? dyn_mech_to_c(path, text, len, NULL, 0, &out, &diag, NULL, NULL)
                          : dyn_mech_derive_text(path, text, len, &out, &diag);
    free(text);
    if (rc != 0) {
        char shown[2048];
        fputs(dyn_lang_diag_format(&diag, shown, sizeof shown), stderr);
        return rc == 1 ? CLI_FAILED : CLI_USAGE;
    }
    if (!c_path) {
        fputs(out, stdout);
        free(out);
        return CLI_OK;
    }
    /* a temporary file renamed over FILE.c once written whole, as run's outputs are */
    cli_out f;
    int wrc = cli_out_open(&f, "--c", c_path);
    if (wrc == CLI_OK) {
        const int bad = fputs(out, f.f) < 0;
        wrc = cli_out_close(&f, !bad);
    }
    free(out);
    return wrc;
}
