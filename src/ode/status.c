/* SPDX-License-Identifier: BSD-3-Clause */
/* Names of solve statuses, for messages. */
#include "dynkit/ode.h"

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
