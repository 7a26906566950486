"""The Python side of the compiled steps (``cablefem.compiled.steps``): a ``Packer`` packs a ``Group`` of
strings (``cablefem.dynamics.group``: their integrators, schemes, compiled kernels, seabed and
junctions) into the compiled ``Group`` the policy runs on, and hands the results back."""

import numba
import numpy as np

from cablefem.compiled import kernels
from cablefem.compiled.seabed import GRID, PLANE, TRIANGULATED, Projector
from cablefem.compiled.steps import FRACTIONS, SLOTS, Group, Problem, bound, fill_calls, strings_list

#: adaptive steps in the compiled loop end on this many even splits of an output interval (smaller
#: ones go on in Python, where the ends are placed anywhere)
ADAPTIVE_PARTS = 64
#: the times and forces of an attempt's call (``Packer.attempt``), which has none
NO_TIMES, NO_FORCES = np.zeros(0), np.zeros((0, 1, 2, 3))
from cablefem.dynamics import policy
from cablefem.geometry import DepthGrid, TriangulatedSurface
from cablefem.geometry import _walk_jit as walk


def projector_kind(integ):
    """How the compiled steps project ``integ``'s seabed (PLANE, GRID, TRIANGULATED), or None where
    they cannot (the numpy evaluator; a seabed without a compiled projection)."""
    ev, seabed = integ.evaluator, integ.system.seabed
    if not ev.compiled:
        return None
    if ev.plane.size:
        return PLANE
    if isinstance(seabed, DepthGrid) and seabed.compiled:
        return GRID
    if isinstance(seabed, TriangulatedSurface) and seabed.compiled:
        return TRIANGULATED
    return None


try:
    from numba._dispatcher import compute_fingerprint as _fingerprint
except ImportError:  # not numba's public face: its fallback is
    _fingerprint = numba.typeof


def type_key(problem):
    """A key of ``problem``'s numba type, cheap enough for every run of steps: the fingerprint numba's
    dispatcher selects its compiled code by (~10 us; ``numba.typeof``, its fallback, takes ~2 ms).
    The addresses in a ``calls`` table are those of code compiled for one type: a Problem of another
    (a settings field that became an int) needs the table filled again."""
    return _fingerprint(problem)


class _String:
    """What one string keeps between compiled runs: its arrays and scratch, its seabed's projector kind."""

    def __init__(self, integ, kind, ends, interior, increment_scale):
        fem, ev = integ.fem, integ.evaluator
        self.integ, self.kind, self.ev = integ, kind, ev
        self.seabed = integ.system.seabed
        nel, nq = ev.full.dx.shape
        if kind == PLANE:  # the kernel computes the gap itself
            self.bed = kernels.Bed(ev.plane, *ev.unused)
        else:  # written by ``project`` each evaluation
            self.bed = kernels.Bed(ev.plane, np.zeros((nel, nq)), np.zeros((nel, nq, 3)), np.zeros((nel, nq, 3)),
                                   np.zeros((nel, nq, 3, 3)))
        self.end_elements = np.unique(np.flatnonzero(np.isin(ev.mesh.dofs, fem.end_dofs).any(axis=1))).astype(np.int64)
        self.points = nel * nq
        self.rule = fem.full  # positions at its quadrature points: the walk's start
        n, N = ev.n, fem.n_dofs
        size = n * (2 * ev.kl + ev.ku + 1)
        self.vectors = tuple(np.zeros(n) for _ in range(3))  # rhs, step, original
        self.bands = (np.zeros(size), np.zeros(size), np.zeros(n, dtype=np.int64), np.empty(ev.kl + 1))
        self.rows = tuple(np.zeros((N, 3)) for _ in range(6))  # X1, Xe, Ve, Ae, guess, base
        pts = ev.points
        self.keeps = ((kernels.byte_view(ev.base_full), kernels.byte_view(pts.full_state)),
                      (kernels.byte_view(ev.base_reduced), kernels.byte_view(pts.reduced_state)))
        kept, nothing = integ.system.kept_history(), np.zeros(0, dtype=np.uint8)  # commit what a load keeps
        self.commits = tuple((kernels.byte_view(old), kernels.byte_view(new)) if rule in kept else (nothing, nothing)
                             for rule, (old, new) in (("full", (pts.full_old, pts.full_new)),
                                                      ("reduced", (pts.reduced_old, pts.reduced_new))))
        self.factors = np.full(1, np.nan, dtype=policy.FACTORS)  # kept between runs
        self.interior = np.asarray(interior, dtype=np.int64)
        self.increment_scale = float(increment_scale)
        self.EA = np.ascontiguousarray(integ.system.props["EA"], dtype=float)
        # its junction ends: (band row, junction, node), -1 where unused; Z, S, yE of the condensation
        self.junction_ends = np.full((2, 3), -1, dtype=np.int64)
        order = list(ev.free_order)
        for s, (_, _, j, dof) in enumerate(ends):
            self.junction_ends[s] = (order.index(dof), j, dof)
        self.junction = (np.zeros((n, 6)), np.zeros((6, 6)), np.zeros(6))

    def projector(self, X):
        """The seabed's ``Projector`` for state X (N, 3): its arrays, the walk's warm start from the
        seabed's last call at these points, and scratch."""
        n = self.points
        zero1, zero2 = np.zeros(1), np.zeros((1, 1))
        grid = (self.seabed.x, self.seabed.y, self.seabed.z) if self.kind == GRID else (zero1, zero1, zero2)
        if self.kind == TRIANGULATED:
            surface, typical, start = self.seabed.walk_start(self.rule.interpolate(X)[0])
        else:  # unused, typed as the walk's own
            surface, typical = walk.Surface(zero2, np.zeros((1, 3), dtype=np.int64), zero1, zero1), 0.0
            start = walk.Start(np.zeros((3, n)), np.zeros(n, dtype=np.int64), np.zeros(n), np.zeros(n, dtype=bool))
        result = walk.Result(np.zeros(n, dtype=np.int64), np.zeros((3, n)), np.zeros((walk.OUTPUTS, n)))
        return Projector(self.kind, *grid, surface, typical, start, result, np.zeros((3, n)))

    def problem(self, settings, ends, fractions, calls):
        """The ``Problem`` of the integrator's current state, the anchor and fairlead at the ends of the
        steps to come (m, 2, 3) and at their splits (m, FRACTIONS - 1, 2, 3), calling the functions at
        ``calls`` (``steps.CALLS``)."""
        integ, ev, fem = self.integ, self.ev, self.integ.fem
        clock = integ.clock.copy()
        clock["t"], clock["last_h"], clock["stopped"], clock["residual"] = integ.t, integ.last_h or 0.0, 0.0, np.nan
        self.factors["auto_left"] = integ.full_steps_left  # "auto" Newton's state, shared with the Python ops
        self.factors["contraction"] = integ.contraction
        state = tuple(np.array(x, dtype=float) for x in (integ.X, integ.V, integ.A, integ.memory, integ.X))
        return Problem(settings, ev.mesh, self.bed, ev.water, ev.points, ev.work, self.projector(integ.X),
                       fem.free_dofs.astype(np.int64), self.interior, ev.free_order, ev.elements, self.end_elements,
                       int(fem.anchor_dof), int(fem.fairlead_dof), integ.scale, self.increment_scale, self.EA, *state,
                       np.zeros_like(integ.X), *self.rows, *self.vectors, *self.bands, ev.base_full,
                       ev.base_reduced, self.keeps, self.commits, clock, self.factors, integ.parameters,
                       np.zeros(len(policy.COUNTERS), dtype=np.int64), np.ascontiguousarray(ends, dtype=float),
                       np.ascontiguousarray(fractions, dtype=float), np.zeros((2, 3)), self.junction_ends,
                       *self.junction, np.array(integ.balance_rows, dtype=float), calls)

    def finish(self, prob):
        """Hand the run's results back to the integrator: counters, "auto"'s state, the seabed walk's
        last call and, if a step was taken, the state and the rows of the converged point, which
        the reactions read (``Scheme.rows_at_state``)."""
        integ, counters, clock = self.integ, prob.counters, prob.clock[0]
        integ.full_steps_left = float(self.factors["auto_left"][0])
        integ.contraction = float(self.factors["contraction"][0])
        if self.kind == TRIANGULATED and counters[policy.NFEV]:  # the walk's last call: the next one starts there
            self.seabed.walk_end(prob.projector.start)
        integ.counters += counters
        integ.last_residual = float(clock["residual"])
        if clock["t"] != integ.t:
            integ.X, integ.V, integ.A, integ.prediction = prob.X, prob.V, prob.A, prob.prediction
            integ.memory, integ.balance_rows = prob.memory, prob.balance_rows
            integ.residual_rows = prob.rows if integ.scheme.rows_at_state else None
            integ.t, integ.last_h = float(clock["t"]), float(clock["last_h"])
        integ.clock = prob.clock
        # the last attempt's factors, as the Python face leaves them (``Integrator.begin``)
        integ.factors = (float(clock["v_x"]), float(clock["a_x"]), float(clock["g_x"]))
        integ.t_eval = float(clock["t_eval"])


class Packer:
    """Runs a group's steps through the compiled policy (``cablefem.compiled.steps.bound``); built by
    ``for_group`` where every string can."""

    def __init__(self, group, kinds):
        members = group.members
        self.group = group
        # a line alone steps on its string's Problem, strings that meet at junctions on a Group
        self.kind = "group" if group.junctions or len(members) > 1 else "line"
        self.functions = bound(members[0].scheme)[self.kind]
        self.strings = [_String(m, kind, ends, interior, scale) for m, kind, ends, interior, scale
                        in zip(members, kinds, group.ends, group.interior, group.increment_scale)]
        # the splits of a step where the ends are known: a fixed step halved DEPTH times, or the
        # adaptive steps' grid in an output interval (``policy.advance``)
        self.parts = ADAPTIVE_PARTS if members[0].adaptive else FRACTIONS
        self.settings = members[0].make_settings(self.parts)  # read at construction
        J = len(group.names)
        leaders = [(k, members[k].fem.end_dofs[end]) for k, end in (group.junctions[name][0] for name in group.names)]
        self.leaders = np.array(leaders, dtype=np.int64).reshape(-1, 2)
        self.scratch = (np.zeros(3 * J), self.leaders, np.zeros((J, 3)), np.zeros((J, 3)), group.scale,
                        np.zeros((3 * J, 3 * J)), np.zeros((6, 6)), np.zeros((6, 6)), np.zeros(6), np.zeros(6))
        self.junctions = J
        #: the addresses of what the compiled steps call (``steps.CALLS``), shared by every Problem and Group
        self.calls = np.zeros(SLOTS, dtype=np.int64)
        self.called = None  # the type key the table was filled for (``type_key``)

    @classmethod
    def for_group(cls, group):
        """A packer for ``group`` when every string evaluates with the compiled kernel on a plane, a
        depth grid or a triangulated surface with compiled projections, all with one scheme; None
        otherwise (the Python ops apply)."""
        kinds = [projector_kind(m) for m in group.members]
        if None in kinds or len({m.scheme for m in group.members}) > 1:
            return None
        return cls(group, kinds)

    def ends(self, times):
        """Per string, the anchor and fairlead at ``times`` (m,) and where the loop may split each step
        (halved on failure), (m, 2, 3) and (m, FRACTIONS - 1, 2, 3)."""
        out = []
        for string in self.strings:
            integ = string.integ
            starts = np.append(integ.t, times[:-1])
            split = np.arange(1, self.parts) / self.parts
            fractions = integ.end_positions((starts[:, None] + split * (times - starts)[:, None]).ravel())
            out.append((integ.end_positions(times), fractions.reshape(len(times), self.parts - 1, 2, 3)))
        return out

    def pack(self, ends):
        """What the compiled policy steps: a line's ``Problem``, or the ``Group`` of the strings'
        current states; each string's ends (``ends``)."""
        self.problems = [string.problem(self.settings, *each, self.calls) for string, each in zip(self.strings, ends)]
        prob = self.problems[0] if self.kind == "line" else Group(self.settings, strings_list(self.problems),
                                                                   self.junctions, *self.scratch, self.calls)
        key = type_key(self.problems[0])  # the strings' type (and with it the Group's): the table's
        if key != self.called:
            fill_calls(self.functions, prob, self.problems, self.calls)
            self.called = key
        return prob

    def finish(self):
        """Hand each string's results back from the Problems ``pack`` made (``_String.finish``)."""
        for string, each in zip(self.strings, self.problems):
            string.finish(each)

    def run(self, times, forces):
        """Steps of the strings to ``times`` (m,) as ``policy.steps`` takes them, their forces into
        ``forces`` (m, strings, 2, 3). Returns (status, k, the size of the attempt that stopped)."""
        times = np.ascontiguousarray(times, dtype=float)  # the type the compiled steps take (``steps.CALLS``)
        prob = self.pack(self.ends(times))
        status, k = self.functions["entry"](prob, times, forces, 0.0)
        self.finish()
        return status, k, float(self.problems[0].clock[0]["stopped"])

    def attempt(self, h):
        """One attempt of size h of the strings (``policy.attempt``), their ends at t + h; its outcome
        (policy.CONVERGED, DIVERGED or LOST). The attempt's arithmetic is that of a run of steps to the
        time t + h: its size is (t + h) - t."""
        t = self.strings[0].integ.t
        t1 = t + h
        prob = self.pack([(string.integ.ends_at(t1)[None], np.zeros((0, self.parts - 1, 2, 3)))
                          for string in self.strings])
        for each in self.problems:
            each.target[:] = each.ends[0]
        outcome, _ = self.functions["entry"](prob, NO_TIMES, NO_FORCES, t1 - t)
        self.finish()
        return outcome
