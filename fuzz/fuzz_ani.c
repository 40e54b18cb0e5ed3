/* SPDX-License-Identifier: BSD-3-Clause */
/* libFuzzer harness of the .ani reader (dynkit/ani.h): any bytes, read as the animation of
 * a fixed model with one name of each kind, either give primitives whose values evaluate
 * (every value a number or NaN, none written outside the frame) or fail with a diagnostic
 * that formats; nothing may crash, leak or read out of bounds (built with
 * -fsanitize=fuzzer,address,undefined; see fuzz/CMakeLists.txt).
 *   fuzz_ani -max_total_time=300 -dict=fuzz/ani.dict fuzz/corpus/ani */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "dynkit/ani.h"

static const char model[] = "x'=v\nv'=-k*x+w\npar k=2, a=0.5\nnumber c=3\n!d2=2*k\n"
                            "w=x*x+v\nf(u)=u*u+a\ng(u,z)=u+x*z\naux e=x+2*v\ny[1..3]'=-y[j]\n"
                            "done\n";

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    dyn_ani_model m;
    memset(&m, 0, sizeof m);
    m.ode_path = "fuzz.ode";
    m.ode_text = model;
    m.ode_len = sizeof model - 1;
    dyn_ani *a = (dyn_ani *)1;
    dyn_lang_diag d;
    const int rc = dyn_ani_parse("fuzz.ani", (const char *)data, size, &m, &a, &d, NULL, NULL);
    if (rc != 0) {
        if (a != NULL || (rc != 1 && rc != 2))
            abort();
        char buf[2048];
        dyn_lang_diag_format(&d, buf, sizeof buf);
        if (!strstr(buf, "error"))
            abort();
        return 0;
    }
    const int n = dyn_ani_n_values(a);
    double *v = malloc(((size_t)n + 1) * sizeof *v);
    const double y[5] = {0.5, -1, 2, 3, 4}, out[1] = {-1.5}, par[3] = {2, 0.5, 4};
    const dyn_ani_frame fr = {1.25, y, out, par};
    if (!v || dyn_ani_eval(a, &fr, v) != 0)
        abort();
    int sum = 0;
    for (int i = 0; i < dyn_ani_count(a); i++) {
        const dyn_ani_prim *p = dyn_ani_at(a, i);
        if (p->offset != sum || p->n_values < 0 || p->n_values > 5 || !p->text)
            abort();
        sum += p->n_values;
        for (int k = 0; k < p->n_values; k++)
            (void)dyn_ani_value_is_constant(a, i, k);
    }
    if (sum != n)
        abort();
    free(v);
    dyn_ani_free(a);
    return 0;
}
