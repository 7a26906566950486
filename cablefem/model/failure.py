"""Line failures: a line end that lets go during a run (docs/scene.md, "Failures").

A ``Failure`` names the end of one of the scene's lines (a string of a network, ``cablefem.model.network``,
by its index and end) and when it lets go: at a time, when the tension at that end exceeds a threshold,
or at whichever comes first when both are given (MoorDyn-F's FAILURE rows). Only an end whose position
is prescribed can let go (a line's own anchor or fairlead, a fixed or coupled point, a point of a fixed
or coupled body): it then becomes a free end of its line, which ``cablefem.runs.failures`` carries on.
Data only: what reads a failure is ``cablefem.io.failures``.
"""

from dataclasses import dataclass

from cablefem.errors import InputError

#: a failure's end by name, and its index in ``Line.prescribed`` and ``Line.ends``
ENDS = ("anchor", "fairlead")


@dataclass(frozen=True)
class Failure:
    """The end ``end`` ("anchor" or "fairlead") of the line named ``line`` lets go at ``time`` [s] or
    when its tension exceeds ``tension`` [N] (None: that condition is not used; at least one is).
    ``string`` and ``string_end``: the index of the scene's line (the string holding it, in a network)
    and its end (0 anchor, 1 fairlead) that lets go; ``key``: where the failure was written, for
    messages."""

    line: str
    end: str
    time: float | None
    tension: float | None
    string: int
    string_end: int
    key: str = ""

    def describe(self):
        """The failure as summary.json's ``failures`` entries have it (docs/outputs.md)."""
        return {"line": self.line, "end": self.end, "time": self.time, "tension": self.tension}


def releasable(line, end, name, key):
    """InputError unless the end ``end`` (0 anchor, 1 fairlead) of the scene's line ``line`` is held
    in place (its position prescribed), so that letting it go makes it a free end; ``name`` names
    the failure's line for the message."""
    if not line.prescribed[end]:
        point = line.ends[end]
        what = f"at free point '{point}'" if point is not None else "free"
        raise InputError(f"the {ENDS[end]} end of line '{name}' is {what}, not held: only an end at a fixed "
                         "or coupled point, a point of a fixed or coupled body, or a line's own anchor or "
                         "fairlead can let go (a junction of three or more line ends cannot)", key=key)
