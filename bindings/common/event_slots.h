/* SPDX-License-Identifier: BSD-3-Clause */
/* Events of the bindings: dyn_event.g takes no index, so each event of a solve gets its own
 * small function that calls the binding's event(k, t, y, par) with its k.
 * DKB_EVENT_SLOTS(event) defines them and the table dkb_event_slots[DKB_MAX_EVENTS]. */
#ifndef DYNKIT_BINDINGS_EVENT_SLOTS_H
#define DYNKIT_BINDINGS_EVENT_SLOTS_H

#define DKB_MAX_EVENTS 16

#define DKB_EVENT_SLOT(fn, k)                                                                 \
    static double dkb_event_##k(double t, const double *y, void *par) { return fn(k, t, y, par); }

#define DKB_EVENT_SLOTS(fn)                                                                   \
    DKB_EVENT_SLOT(fn, 0)                                                                     \
    DKB_EVENT_SLOT(fn, 1)                                                                     \
    DKB_EVENT_SLOT(fn, 2)                                                                     \
    DKB_EVENT_SLOT(fn, 3)                                                                     \
    DKB_EVENT_SLOT(fn, 4)                                                                     \
    DKB_EVENT_SLOT(fn, 5)                                                                     \
    DKB_EVENT_SLOT(fn, 6)                                                                     \
    DKB_EVENT_SLOT(fn, 7)                                                                     \
    DKB_EVENT_SLOT(fn, 8)                                                                     \
    DKB_EVENT_SLOT(fn, 9)                                                                     \
    DKB_EVENT_SLOT(fn, 10)                                                                    \
    DKB_EVENT_SLOT(fn, 11)                                                                    \
    DKB_EVENT_SLOT(fn, 12)                                                                    \
    DKB_EVENT_SLOT(fn, 13)                                                                    \
    DKB_EVENT_SLOT(fn, 14)                                                                    \
    DKB_EVENT_SLOT(fn, 15)                                                                    \
    static double (*const dkb_event_slots[DKB_MAX_EVENTS])(double, const double *, void *) = { \
        dkb_event_0,  dkb_event_1,  dkb_event_2,  dkb_event_3, dkb_event_4,  dkb_event_5,    \
        dkb_event_6,  dkb_event_7,  dkb_event_8,  dkb_event_9, dkb_event_10, dkb_event_11,   \
        dkb_event_12, dkb_event_13, dkb_event_14, dkb_event_15};

#endif /* DYNKIT_BINDINGS_EVENT_SLOTS_H */
