"""A run's bending outputs: the end moments of the lines with EI > 0 in tensions.csv (a row a step: a
clamped end's reaction, ``Integrator.clamp_moments``, else EI kappa there) and each line's largest
curvature, where and when, in summary.json (docs/outputs.md): ``curvature.curvature_peak`` or a clamped
end's reaction over EI, whichever is larger.

The compiled march returns forces only, so a run with a bending line steps one time step per call
and ``measure`` reads each line's state after every step (``cablefem.runs.run._advance``).
"""

import numpy as np

from cablefem.runs.curvature import curvature_peak
from cablefem.runs.results import LineSampler


class BendingRows:
    """The bending lines of a run (``lines``: the scene's, in order); false when none bends."""

    def __init__(self, lines):
        self.names = [line.name for line in lines]
        self.bends = [any(seg.type.EI > 0 for seg in line.segments) for line in lines]
        self.integrators, self.samplers, self.pending = [], [], []
        #: per line: the largest curvature [1/m], the arc length [m] and the time [s] it occurred at
        self.extremes = {name: {"curvature_max": 0.0, "s": None, "t": None}
                         for name, bends in zip(self.names, self.bends) if bends}

    def __bool__(self):
        return any(self.bends)

    def attach(self, integrators):
        """The run's integrators, one per line, and the points where their curvature is sampled
        (the frames' points, ``LineSampler``)."""
        self.integrators = integrators
        self.ends = [LineSampler(integ.system, [integ.system.line.unstretched_length, 0.0]) if bends else None
                     for integ, bends in zip(integrators, self.bends)]

    def columns(self, prefixed):
        """The tensions.csv columns: each bending line's fairlead and anchor bending moment [N m]."""
        names = ("fairlead_bending_moment", "anchor_bending_moment")
        return [f"{name}:{column}" if prefixed else column
                for name, bends in zip(self.names, self.bends) if bends for column in names]

    def measure(self, t):
        """Read every bending line's state at time t [s]: its end moments, kept for the row of that
        step (``values``), and its curvature against the largest so far."""
        if not self:
            return
        row = []
        for name, integ, ends in zip(self.names, self.integrators, self.ends):
            if ends is None:
                continue
            moments = ends.EI * ends.curvature(integ.X)  # fairlead, anchor: EI kappa, or a clamp's reaction
            reactions = np.linalg.norm(integ.clamp_moments(), axis=1)  # anchor, fairlead
            for k, end in ((0, 1), (1, 0)):
                if integ.system.fem.clamped[end] is not None:
                    moments[k] = reactions[end]
            row += moments.tolist()
            candidates = [curvature_peak(integ.system, integ.X)]
            EI = (ends.EI[1], ends.EI[0])  # anchor, fairlead
            for end, at in ((0, 0.0), (1, integ.system.line.unstretched_length)):  # a clamped end: its reaction
                if integ.system.fem.clamped[end] is not None and EI[end] > 0:
                    candidates.append((reactions[end] / EI[end], at))
            kappa, s = max(candidates, key=lambda c: c[0])
            extreme = self.extremes[name]
            if kappa > extreme["curvature_max"]:
                extreme.update(curvature_max=float(kappa), s=float(s), t=float(t))
        self.pending.append(row)

    def values(self):
        """The end moments of the earliest step measured and not yet written."""
        return self.pending.pop(0)
