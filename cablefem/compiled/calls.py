"""Calls between compiled functions by address: the callee compiled once, not again in every caller,
and only where a scene calls it.

numba links the code of every function a compiled function calls into it, and optimises and
emits it there again: the compiled steps' layers (``steps`` calls ``advance``, which calls
``attempt``, which calls ``newton``, which evaluates the element loop) each compiled again all they
called, and most of a first run's compilation was that (``cablefem.compiled.steps``, "Compile
time"). A call made here goes through the callee's address instead, read at run time from the
caller's first argument (its ``calls``, an int64 array that Python fills with ``address``): the
caller has no copy of the callee's code, and numba's on-disk cache keeps both apart (the address is
data, not code). A callee whose return type is declared is not even compiled with its caller: only
when Python asks for its address, which it does where the scene has what the callee serves (a
seabed to project, a point on the line).

The call is numba's own call of a compiled function (its calling convention, as numba calls a
first-class function by its address): the callee's exceptions reach the caller. The callee is
compiled for declared argument types, to which the caller's values are converted, and ``address``
compiles (or loads) it for the same types, so that the address Python writes is that of the code
the caller was compiled against. Both sides must agree on what the callee returns:
``cablefem.compiled.cache`` deletes every cached kernel when a source of one changes, wherever
numba caches them, so a cached caller never meets a changed callee; and Python fills a ``calls``
table again when the Problems' type changes (``cablefem.compiled.problem.type_key``). A callee
whose return type numba infers as optional (None on some path) cannot be called this way.
"""

from llvmlite import ir
from numba.core import cgutils, types
from numba.extending import intrinsic


def _compiled(dispatcher, argtypes):
    """``dispatcher``'s compiled code for ``argtypes`` (numba types), compiled or loaded from numba's cache."""
    argtypes = tuple(argtypes)
    dispatcher.compile(argtypes)
    return dispatcher.overloads[argtypes]


def address(dispatcher, argtypes, restype=None):
    """The address of ``dispatcher``'s compiled code for ``argtypes`` (``_compiled``); ``restype``: what its
    callers were compiled to expect it to return (a TypeError if it does not)."""
    result = _compiled(dispatcher, argtypes)
    if restype is not None and result.signature.return_type != restype:
        raise TypeError(f"{dispatcher.__name__} returns {result.signature.return_type}, its callers by address "
                        f"expect {restype}")
    return result.library.get_pointer_to_function(result.fndesc.llvm_func_name)


def _returns(dispatcher, argtypes, restype):
    """``restype``, or, if None, what ``dispatcher`` returns for ``argtypes`` (compiling it)."""
    return restype if restype is not None else _compiled(dispatcher, argtypes).signature.return_type


def _call(context, builder, prob, value, slot, restype, argtypes, arguments):
    """Call the code at ``value.calls[slot]`` (``value`` of type ``prob``) with ``arguments``."""
    field = prob.fields.index("calls")
    calls = context.make_array(prob.types[field])(context, builder, value=builder.extract_value(value, field))
    where = builder.load(builder.gep(calls.data, [ir.Constant(ir.IntType(64), slot)]))
    return _call_at(context, builder, where, restype, argtypes, arguments)


def _call_at(context, builder, where, restype, argtypes, arguments):
    """Call the code at address ``where`` (an int64 value) with ``arguments``, propagating its exception."""
    function = context.call_conv.get_function_type(restype, argtypes)
    pointer = builder.inttoptr(where, function.as_pointer())
    status, result = context.call_conv.call_function(builder, pointer, restype, argtypes, arguments)
    with cgutils.if_unlikely(builder, status.is_error):
        context.call_conv.return_status_propagate(builder, status)
    return result


def by_address(dispatcher, rest, slot, restype=None):
    """A compiled function (a numba intrinsic) taking what ``dispatcher`` takes, (prob, *rest), that
    calls ``dispatcher``'s code at the address ``prob.calls[slot]``; ``rest``: the numba types of the
    arguments after ``prob`` (the caller's are converted to them); ``restype``: what it returns, or
    None to compile it with its first caller and read it there."""
    rest = tuple(rest)

    def typed(prob):
        argtypes = (prob,) + rest
        returns = _returns(dispatcher, argtypes, restype)

        def codegen(context, builder, sig, values):
            return _call(context, builder, prob, values[0], slot, returns, argtypes, values)

        return returns(*argtypes), codegen

    # one definition per arity: numba's intrinsics take no *args
    if len(rest) == 0:
        def call(typingctx, prob):
            return typed(prob)
    elif len(rest) == 1:
        def call(typingctx, prob, a):
            return typed(prob)
    elif len(rest) == 2:
        def call(typingctx, prob, a, b):
            return typed(prob)
    elif len(rest) == 3:
        def call(typingctx, prob, a, b, c):
            return typed(prob)
    else:
        raise ValueError(f"by_address calls functions of 1 to 4 arguments, not {len(rest) + 1}")
    call.__name__ = call.__qualname__ = f"{dispatcher.__name__}_by_address"
    return intrinsic(call)


def through(dispatcher, types_of, slot, restype=None):
    """A compiled function (a numba intrinsic) ``call(prob, arguments)`` that calls
    ``dispatcher(*arguments)`` at the address ``prob.calls[slot]``; ``types_of(prob's type)``: the
    numba types of the arguments (the caller's tuple is converted to them); ``restype`` as for
    ``by_address``."""

    def call(typingctx, prob, arguments):
        argtypes = tuple(types_of(prob))
        returns = _returns(dispatcher, argtypes, restype)

        def codegen(context, builder, sig, values):
            unpacked = [builder.extract_value(values[1], k) for k in range(len(argtypes))]
            return _call(context, builder, prob, values[0], slot, returns, argtypes, unpacked)

        return returns(prob, types.Tuple(argtypes)), codegen

    call.__name__ = call.__qualname__ = f"{dispatcher.__name__}_through"
    return intrinsic(call)


def at(argtypes, restype):
    """A compiled function (a numba intrinsic) ``call(where, arguments)`` that calls the code at the
    address ``where`` (int64) with ``arguments``, converted to ``argtypes``, returning ``restype``: a
    table of functions of one signature (the loads' point kernels, ``cablefem.compiled.kernels``),
    each compiled where Python writes its address (``address``, with ``restype``)."""
    argtypes = tuple(argtypes)

    def call(typingctx, where, arguments):
        def codegen(context, builder, sig, values):
            unpacked = [builder.extract_value(values[1], k) for k in range(len(argtypes))]
            return _call_at(context, builder, values[0], restype, argtypes, unpacked)

        return restype(types.int64, types.Tuple(argtypes)), codegen

    return intrinsic(call)
