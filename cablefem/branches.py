"""The branches of a line's piecewise loads, and holding a Newton step on them.

Seabed friction is a ramp up to the slip speed v_c and constant beyond (housner2022 Eq. 5-13),
the seabed spring and its damper act only on points in the seabed and closing on it (desire2023
Eq. 11), a line element pulls only when stretched: each load is smooth on branches with kinks
between them, and at a kink the tangent at one side says nothing of the other. When a full
Newton step is rejected because its trial point crossed such kinks, ``Integrator._newton``
solves it again from its base with the points held on the branches the trial reached (their
value and slope at the base: the semismooth Newton step on those branches). This module says
which: ``hold_branches`` for the per-step Python path (``cablefem.fused.FusedEvaluator``'s
flags), ``branches`` and ``keep_branches`` inside the compiled steps (``cablefem.march``'s
scratch), the same rules; ``cablefem.point_loads._point_loads`` evaluates the held branches.
"""

import numpy as np
from numba import njit

#: branches a point's loads may be held on (``hold`` bits of ``cablefem.point_loads._point_loads``)
STICK, DAMPER_ON, DAMPER_OFF, TOUCH_ON, TOUCH_OFF = 1, 2, 4, 8, 16
DAMPERS, TOUCHES = DAMPER_ON | DAMPER_OFF, TOUCH_ON | TOUCH_OFF
#: a point's contact state (what ``cablefem.point_loads._point_loads`` returns, bits): in the seabed,
#: its damper acting
TOUCHING, CLOSING = 1, 2


def hold_branches(ev, base, again):
    """Hold the branches a rejected Newton step's trial point reached, in the flags ``hold``
    (full points) and ``pull`` (reduced points) of the fused evaluator ``ev``, as ``branches``
    does: friction on its ramp at the full points that slid at the base (|w| >= v_c) and that
    the trial took, still on the seabed, into the ramp or against their slip; the seabed spring
    and damper as the trial has them where it put a point on the seabed or lifted it off (a
    resting point's damper alone switches back and forth); the taut branch at the reduced
    points slack at the base that it pulled taut (with ``again``, also what is held already).
    ``base``: the base's (slip, taut, contact), ``ev``'s own arrays from its evaluation there.
    Returns whether anything is held and the flags changed."""
    base_slip, base_taut, base_contact = base
    before = np.linalg.norm(base_slip, axis=-1)
    after = np.linalg.norm(ev.slip, axis=-1)
    turned = np.einsum("eqa,eqa->eq", base_slip, ev.slip) <= 0.0
    hold = np.where((before >= ev.bed[5]) & (after > 0.0) & ((after < ev.bed[5]) | turned), STICK, 0)
    contact = np.where(ev.contact & TOUCHING, TOUCH_ON, TOUCH_OFF) | np.where(ev.contact & CLOSING, DAMPER_ON,
                                                                              DAMPER_OFF)
    hold |= np.where((ev.contact ^ base_contact) & TOUCHING, contact, 0)  # not the damper alone
    pull = ~base_taut & ev.taut
    if again:
        hold |= np.where(hold & (TOUCHES | DAMPERS), ev.hold & STICK, ev.hold)
        pull |= ev.pull
    hold = hold.astype(np.int8)
    changed = not (np.array_equal(hold, ev.hold) and np.array_equal(pull, ev.pull))
    ev.hold[:], ev.pull[:] = hold, pull
    return bool(hold.any() or pull.any()) and (changed or not again)


@njit(cache=True, _nrt=False)
def keep_branches(scratch):
    """The base point's slip velocities, taut points and contact states, for ``branches``."""
    slip, taut, base_slip, base_taut, contact, base_contact = scratch[9:15]
    for e in range(slip.shape[0]):
        for g in range(slip.shape[1]):
            for a in range(3):
                base_slip[e, g, a] = slip[e, g, a]
            base_contact[e, g] = contact[e, g]
        for g in range(taut.shape[1]):
            base_taut[e, g] = taut[e, g]


@njit(cache=True, _nrt=False)
def branches(scratch, vc, again):
    """Hold (scratch's hold and pull flags) the branches a rejected Newton step's trial point
    reached, as ``hold_branches``: friction on its ramp at the full points that slid at the
    base (|w| >= vc) and that the trial took, still on the seabed, into the ramp or against their
    slip; the seabed spring and damper as the trial has them where it put a point on the seabed
    or lifted it off; the taut branch at the reduced points slack at the base that it pulled
    taut (with ``again``, also what is held already). Returns whether anything is held and the
    flags changed."""
    hold, pull, slip, taut, base_slip, base_taut, contact, base_contact = scratch[7:15]
    held, changed = False, False
    for e in range(slip.shape[0]):
        for g in range(slip.shape[1]):
            before = np.sqrt(_dot3(base_slip[e, g], base_slip[e, g]))
            after = np.sqrt(_dot3(slip[e, g], slip[e, g]))
            flag = 0
            if before >= vc and after > 0.0 and (after < vc or _dot3(base_slip[e, g], slip[e, g]) <= 0.0):
                flag |= STICK
            now = contact[e, g]
            if ((now ^ base_contact[e, g]) & TOUCHING) != 0:  # not the damper alone: resting points chatter
                flag |= (TOUCH_ON if (now & TOUCHING) != 0 else TOUCH_OFF) | (
                    DAMPER_ON if (now & CLOSING) != 0 else DAMPER_OFF)
            if again:
                flag |= hold[e, g] if (flag & (TOUCHES | DAMPERS)) == 0 else hold[e, g] & STICK
            changed = changed or flag != hold[e, g]
            hold[e, g] = flag
            held = held or flag != 0
        for g in range(taut.shape[1]):
            flag = (taut[e, g] and not base_taut[e, g]) or (again and pull[e, g])
            changed = changed or flag != pull[e, g]
            pull[e, g] = flag
            held = held or flag
    return held and (changed or not again)


@njit(cache=True, inline="always", _nrt=False)
def _dot3(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
