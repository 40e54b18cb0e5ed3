/* SPDX-License-Identifier: BSD-3-Clause */
/* Names of solve statuses, for messages, and the failure of a result (result_fail.h). */
#include <stdarg.h>
#include <stdio.h>

#include "dynkit/ode.h"
#include "ode/result_fail.h"

int dyn_result_fail(dyn_result *res, int status, const char *fmt, ...)
{
    va_list ap;
    res->status = status;
    va_start(ap, fmt);
    vsnprintf(res->message, sizeof res->message, fmt, ap);
    va_end(ap);
    return status;
}

const char *dyn_status_name(int status)
{
    switch (status) {
    case DYN_OK: return "ok";
    case DYN_ERR_ARG: return "bad argument";
    case DYN_ERR_RHS: return "right-hand side failed";
    case DYN_ERR_NONFINITE: return "state not finite";
    case DYN_STOPPED: return "stopped by output";
    case DYN_ERR_IO: return "output error";
    case DYN_CANCELLED: return "cancelled";
    case DYN_ERR_STEP_SIZE: return "step size underflow";
    case DYN_ERR_MAX_STEPS: return "too many steps";
    case DYN_ERR_CAPACITY: return "recorder full";
    case DYN_ERR_ZENO: return "resets accumulate (Zeno)";
    default: return "unknown status";
    }
}
