/* SPDX-License-Identifier: BSD-3-Clause */
/* result_fail.h — the failure of a solve's result, for the drivers (private; status.c). */
#ifndef DYNKIT_SRC_ODE_RESULT_FAIL_H
#define DYNKIT_SRC_ODE_RESULT_FAIL_H

#include "dynkit/ode.h"

/* Set res->status and res->message (printf-style); returns status. */
#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
int dyn_result_fail(dyn_result *res, int status, const char *fmt, ...);

#endif /* DYNKIT_SRC_ODE_RESULT_FAIL_H */
