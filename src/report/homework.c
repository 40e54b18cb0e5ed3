/* SPDX-License-Identifier: BSD-3-Clause */
/* dyn_homework_compute: all four problems of the homework, timed. */
#include <string.h>
#include <time.h>

#include "report/hw_common.h"

int dyn_homework_compute(dyn_homework *hw, char *err, size_t errlen)
{
    clock_t start = clock();
    memset(hw, 0, sizeof *hw);
    int rc = dyn_hw_pendulum_compute(&hw->pendulum, err, errlen);
    rc = rc ? rc : dyn_hw_vanderpol_compute(&hw->vanderpol, err, errlen);
    rc = rc ? rc : dyn_hw_plane_compute(&hw->plane, err, errlen);
    rc = rc ? rc : dyn_hw_cart_compute(&hw->cart, err, errlen);
    hw->compute_seconds = (double)(clock() - start) / CLOCKS_PER_SEC;
    return rc;
}
