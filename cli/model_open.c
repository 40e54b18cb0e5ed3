/* MODEL arguments of the commands: a built-in model's name, with "did you mean" for typos.
 * (Model files, .ode and .c, are opened here too: see the model-file layers.) */
#include <string.h>

#include "cli.h"
#include "dynkit/lang.h"

static int unknown_model(const char *command, const char *spec)
{
    const char *names[64];
    char list[512];
    int n = dyn_model_count() < 64 ? dyn_model_count() : 64;
    for (int i = 0; i < n; i++)
        names[i] = dyn_model_at(i)->name;
    const char *near = dyn_lang_nearest(spec, names, n);
    dyn_model_names(list, sizeof list);
    if (near)
        return cli_usage_error(command, "unknown model '%s' (did you mean '%s'? accepted: %s)",
                               spec, near, list);
    return cli_usage_error(command, "unknown model '%s' (accepted: %s)", spec, list);
}

int cli_model_open(const char *command, const char *spec, const dyn_model **model)
{
    *model = dyn_model_find(spec);
    return *model ? CLI_OK : unknown_model(command, spec);
}
