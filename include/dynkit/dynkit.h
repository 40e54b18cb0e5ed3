/* SPDX-License-Identifier: BSD-3-Clause */
/* dynkit/dynkit.h — everything of the dynkit library in one include. */
#ifndef DYNKIT_DYNKIT_H
#define DYNKIT_DYNKIT_H

#include "dynkit/ode.h"
#include "dynkit/solve.h"
#include "dynkit/ivp.h"
#include "dynkit/run.h"
#include "dynkit/model.h"
#include "dynkit/models.h"
#include "dynkit/cart.h"
#include "dynkit/plane.h"
#include "dynkit/problems.h"
#include "dynkit/io.h"
#include "dynkit/report.h"
#include "dynkit/verify.h"

#endif
