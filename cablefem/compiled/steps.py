"""Time steps on the compiled kernel, many in one numba call: the Newton policy bound to its compiled ops.

``cablefem.dynamics.policy`` writes the Newton policy once (iterations, line search, branch
corrections, retries, halving and growth); ``bound(scheme)`` binds it to the compiled ops on one
string (``cablefem.compiled.line_ops``) or on a group (``cablefem.compiled.group_ops``), with a
scheme's arithmetic (``cablefem.dynamics.scheme``: BDF2, generalised-alpha, or any scheme a
file defines), and compiles it. The policy steps a ``Group`` of strings: a line alone is a group of
one; the strings that meet at junction points are a group whose junctions are solved with them,
each string condensed onto its junction ends (``cablefem.dynamics.group``). Runs of steps go without
returning to Python, with the numbers of the Python ops (``cablefem.dynamics.python_ops``) to
round-off (tests/test_march.py, tests/test_march_alpha.py, tests/test_junction_steps.py).

The banded LU is ``cablefem.compiled.banded`` (LAPACK's dgbtf2/dgbtrs written out: numba cannot cache
a ctypes call to LAPACK). The seabed is projected in the loop too (``cablefem.compiled.seabed``);
where the walk cannot place a point, the loop stops and that step goes on in Python, whose search
finds it.

Compile time. The ops that read the scheme are compiled once per scheme (``bound``): they are rebound
to the scheme's functions, under names that carry the scheme's name and a hash of its code, so that each
binding has its own on-disk cache. The strings of a group have one numba type (the catalog's records
and the seabed's projector are the same for every line; only sizes differ), so they come in numba's
typed List (``strings_list``), whose type does not hold their number: one compilation serves every
network. A tuple's does (each size compiled the group's steps again, minutes each, longer the more
strings), and ``numba.literal_unroll`` versions each loop body per element. No numba runtime on a
string, nor on a line's policy (the small solves' scratch is in the group; the group's ops and policy
have it for the List), and no literal arguments (each compiles a callee once more: ``policy.FLAG``).
numba links the code of every callee into its caller and optimises and compiles it there again, so
each layer of the policy (steps, advance, attempt, newton) cost again all it called, the element
loop among it, 3-5 s of the first run each: the layers call each other by address (``CALLS``,
``cablefem.compiled.calls``; ``advance`` is inlined into ``steps``), and so does a string's evaluation call the element loop, the seabed's
projection and the node loads (``THROUGH``): each compiled once, its address in the ``calls`` of
the ``Problem`` and ``Group`` (``fill_calls``), the projection and the node loads only for a scene
that has them. Python calls one function (``_entry``: numba's Python wrapper unboxes the ``Problem``
in code as large as a layer's), the others have no Python wrapper, none has a C wrapper.
"""

import hashlib
import sys
from collections import namedtuple
from types import FunctionType, ModuleType

import numba
from numba import njit, types
from numba.typed import List

from cablefem.compiled import calls, group_ops, line_ops
from cablefem.compiled.line_ops import LAYER_SLOTS, THROUGH
from cablefem.dynamics import policy

#: a step of the compiled loop may be halved this many times (the ends' positions at the
#: 2**DEPTH - 1 points that split each step evenly are given); deeper, the Python ops go on
DEPTH = 3
FRACTIONS = 2 ** DEPTH

#: one string (``cablefem.compiled.problem.Packer``): the policy's settings, the kernel's records (mesh, bed, water,
#: pts, work) and the seabed's projector; its free nodes, those of them that are not junction ends
#: (``interior``), the free unknowns in band order, all and the end elements, the anchor and fairlead
#: nodes, its residual scale, the factor that puts its increments in the group's increment
#: tolerance and the axial stiffness per element [N] (the error control's tension scale); the state X, V, A, the scheme's memory (MEMORY, N, 3), the last predictor and the rows
#: M A + G (N, 3), updated in place; the trial X1, the evaluation point Xe, Ve, Ae, the guess and
#: Newton's base (N, 3); the increment, Newton's
#: step and its own step when corrected (n,); the band and its LU (flat, LAPACK's column-major
#: layout), pivots and multipliers; the base's branch state; the byte views (dst, src) that keep the
#: branch state as the base's and commit the trial history; the clock (``policy.CLOCK``), the kept
#: factors' key (``policy.FACTORS``), the scheme's record, counters (``policy.COUNTERS``); the anchor
#: and fairlead at the end of each step (m, 2, 3), at its splits (m, FRACTIONS - 1, 2, 3) and at the
#: end of the attempt (2, 3); its junction ends, (2, 3) rows of (band row, junction, node), -1 where
#: unused, the columns Z (n, 6) of K^-1 there, their end stiffness S (6, 6) and the string's own step
#: there yE (6,); the last balance's fairlead and anchor rows and what the reactions add to them
#: (2, 2, 3) (``Integrator.balance_rows``); the addresses of the functions its ops call (``CALLS``)
Problem = namedtuple("Problem", "settings mesh bed water pts work projector free_nodes interior free_order all_elements "
                                "end_elements anchor_node fairlead_node scale increment_scale EA "
                                "X V A memory prediction rows X1 Xe Ve Ae guess base "
                                "rhs step original band lu ipiv multipliers base_full base_reduced keeps commits "
                                "clock factors scheme counters ends fractions target junction_ends Z S yE "
                                "balance_rows calls")
#: the strings stepped together: the policy's settings, the strings (numba's typed List of ``Problem``:
#: ``strings_list``), the number of junctions, their step dq (3 J,), the string and node whose predictor
#: places each junction (J, 2) and that place (J, 3), the junctions' balance (J, 3), the group's
#: residual scale, and scratch of the small solves: the junctions' system (3 J, 3 J), a string's end
#: columns ZE and their inverse's work (6, 6), a column and a correction mu (6,); the addresses of the
#: functions its ops call (``CALLS``)
Group = namedtuple("Group", "settings strings junctions dq leaders at balance scale system ZE work column mu calls")

#: the policy's layers called by address (``cablefem.compiled.calls``: compiled once, not again in each caller):
#: the slot of each in the ``calls`` of the prob the policy steps (a line's ``Problem`` or a ``Group``), and
#: the types of its arguments after the prob: ``newton`` from ``attempt``, ``attempt`` from ``advance`` (and
#: on its own from ``_entry``), ``steps`` from ``_entry``. Only these: a call by address copies the
#: ``Problem``'s array descriptors as arguments (~900 words), here once an attempt; the string's evaluation
#: and Newton increment, once an iteration, are linked into ``newton`` (by address they cost the steps 0.7 %
#: more instructions)
CALLS = {"newton": (0, (types.boolean, types.int64)), "steps": (1, (types.float64[::1], types.float64[:, :, :, ::1])),
         "attempt": (2, (types.float64,))}
#: the layers inlined into their one caller: ``advance`` into ``steps`` (``attempt`` into ``advance`` too would
#: save 0.35 % of the steps' instructions and cost the first run 4 s: ``benchmarks/startup.py``)
INLINED = ("advance",)
assert len(CALLS) == LAYER_SLOTS  # THROUGH's slots follow the layers'
SLOTS = len(CALLS) + len(THROUGH)


@njit(cache=True)
def _new_strings(first):
    strings = List()
    strings.append(first)
    return strings


@njit(cache=True)
def _append_string(strings, p):
    strings.append(p)


def strings_list(problems):
    """The ``Problem`` of each string of a group in numba's typed List (their arrays shared, not
    copied), made and filled by compiled functions cached on disk (a List's own methods compile in
    every process)."""
    strings = _new_strings(problems[0])
    for p in problems[1:]:
        _append_string(strings, p)
    return strings


# ------------------------------------------------------------------------ bound per scheme
#: the ops the policy calls (``cablefem.dynamics.policy``'s docstring), besides ``attempt``: on a
#: string these names, on a group ``group_`` and these names
OPS = ("evaluate", "norm", "increment", "factors_current", "forget_factors", "take_step", "set_base",
       "restore_base", "hold", "save_original", "restore_original", "finish", "begin", "restart", "accept",
       "auto_left", "set_auto_left", "contraction", "set_contraction", "count", "time", "last_step",
       "record_residual", "record_stop", "place_ends", "reactions", "error", "last_error", "record_error",
       "proposal", "set_proposal")
#: the functions that read the scheme, directly or through another: copied per scheme by ``bound``
#: (each one's callees before it)
SCHEMED = ("_assemble", "evaluate", "finish", "begin", "accept", "_forces", "reactions", "error", "group_evaluate",
           "group_finish", "group_begin", "group_accept", "group_reactions", "group_error")
_BOUND = {}


def _tag(scheme):
    """The scheme's name and a hash of its functions' code: the bound functions' cache names."""
    digest = hashlib.sha256(scheme.parameters.str.encode() + str(scheme.memory).encode()
                            + str(scheme.rows_at_state).encode())
    for function in (scheme.begin, scheme.point, scheme.accept, scheme.error):
        code = function.py_func.__code__
        digest.update(code.co_code + repr(code.co_consts).encode() + repr(code.co_names).encode())
    return "".join(c if c.isalnum() else "_" for c in scheme.name) + "_" + digest.hexdigest()[:10]


_attempt_call = _steps_call = None  # bound per scheme and kind (``bound``)


def _entry(prob, times, forces, h):
    """Python's one way into the compiled policy: with h > 0 one attempt of size h (``policy.attempt``;
    its outcome, 0), else steps to ``times`` (``policy.steps``). One function with numba's Python
    wrapper, whose unboxing of the ``Problem`` or ``Group`` is as large as a layer: it was compiled
    for ``attempt`` and ``steps`` each."""
    if h > 0.0:
        return _attempt_call(prob, h), 0
    return _steps_call(prob, times, forces)


def _compiler(kind):
    """numba's njit for the policy's functions on a ``kind`` ("line", "group"): numba's runtime only
    on a group (its strings' typed List; a line's ``Problem`` holds arrays Python owns, and with the
    runtime every op copying it counts references to its ~50 arrays: 15 s more compilation of the
    first run), no Python wrapper (Python calls them through ``_entry``), no C wrapper (the
    module's docstring, "Compile time"), and ``INLINED`` into their caller."""
    def compile(function):
        return njit(cache=True, _nrt=kind == "group", no_cpython_wrapper=True, no_cfunc_wrapper=True,
                    inline="always" if function.__name__ in INLINED else "never")(function)
    return compile


def bound(scheme):
    """The policy's functions (``policy.FUNCTIONS``: newton, attempt, advance, steps) bound to the ops
    of ``line_ops`` and ``group_ops`` and to ``scheme``'s arithmetic, compiled: {"line": on a string's ``Problem``, "group": on a
    ``Group``}; one pair per scheme, made on first use (each compiled on its first call)."""
    tag = _tag(scheme)
    if tag in _BOUND:
        return _BOUND[tag]
    module = sys.modules[__name__]
    namespace = dict(vars(line_ops), **vars(group_ops))  # the ops' globals, the copies' globals once bound
    namespace.update(scheme_begin=scheme.begin, scheme_point=scheme.point, scheme_accept=scheme.accept,
                     scheme_error=scheme.error, ROWS_AT_STATE=scheme.rows_at_state)
    for name in SCHEMED:  # in this order: each one's callees first
        original = getattr(group_ops if name.startswith("group_") else line_ops, name)
        function = FunctionType(original.py_func.__code__, namespace, name, original.py_func.__defaults__)
        function.__qualname__ = f"{tag}.{name}"
        function.__module__ = original.__module__  # (the namespace's __name__ is group_ops')
        options = {key: value for key, value in original.targetoptions.items() if key != "nopython"}
        namespace[name] = njit(cache=True, **options)(function)
    functions = {}
    for kind, prefix in (("line", ""), ("group", "group_")):
        ops = ModuleType(f"{__name__}.{tag}.{kind}")
        for name in OPS:
            setattr(ops, name, namespace[prefix + name])
        functions[kind] = policy.bind(ops, compile=_compiler(kind), name=f"{kind}_{tag}", link=_link)
        ops.attempt = _link("attempt", functions[kind]["attempt"])
        entry = {"_attempt_call": ops.attempt,
                 "_steps_call": _link("steps", functions[kind]["steps"])}
        function = FunctionType(_entry.__code__, dict(vars(module), **entry), "entry")
        function.__qualname__ = f"{kind}_{tag}.entry"
        functions[kind]["entry"] = njit(cache=True, _nrt=kind == "group", no_cfunc_wrapper=True)(function)
    _BOUND[tag] = functions
    return functions


def _link(name, function):
    """What the policy's functions call in place of its layer ``name`` (``policy.bind``): ``function``
    by address (``CALLS``), or itself where it is inlined (``INLINED``)."""
    if name in INLINED:
        return function
    slot, rest = CALLS[name]
    return calls.by_address(function, rest, slot)


def fill_calls(functions, prob, strings, table):
    """Write into ``table`` (the ``calls`` of ``prob`` and of its strings) the addresses of the policy's
    layers of ``functions`` (a kind's of ``bound``; ``CALLS``) for ``prob`` (a line's ``Problem`` or a
    ``Group``), and of what the ``strings`` (their ``Problem``s, one type) call with the arguments it
    names (``THROUGH``) where one needs it, each compiled or loaded for those types."""
    string = numba.typeof(strings[0])
    whole = numba.typeof(prob) if prob is not strings[0] else string
    for name, (slot, rest) in CALLS.items():
        table[slot] = calls.address(functions[name], (whole,) + rest)
    for entry in THROUGH.values():
        if entry.needed is None or any(entry.needed(p) for p in strings):
            table[entry.slot] = calls.address(entry.function, entry.types_of(string), entry.returns)
