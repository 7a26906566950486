"""Calls between compiled functions by address: the callee compiled once, not again in every caller.

numba links the code of every function a compiled function calls into it, and optimises and
emits it there again: the compiled steps' layers (``steps`` calls ``advance``, which calls
``attempt``, which calls ``newton``, which evaluates the element loop) each compiled again all they
call, and most of a first run's compilation was that (``cablefem.compiled.steps``, "Compile
time"). ``by_address`` makes a call that goes through the callee's address instead, read at run
time from the caller's first argument (its ``calls``, an int64 array that Python fills with
``address``): the caller has no copy of the callee's code, and numba's on-disk cache keeps both
apart (the address is data, not code).

The call is numba's own call of a compiled function (its calling convention, as numba calls a
first-class function by its address): the callee's exceptions reach the caller. The callee is
compiled for the caller's first argument's type and the declared types of the others, to which the
caller's values are converted; ``address`` compiles (or loads) it for the same types, so that the
address Python writes is that of the code the caller was compiled against. Both sides must agree
on what the callee returns: ``cablefem.compiled.cache`` deletes every cached kernel when a source
of one changes, so a cached caller never meets a changed callee.
"""

import numba
from llvmlite import ir
from numba.core import cgutils, types
from numba.extending import intrinsic


def address(dispatcher, argtypes):
    """The address of ``dispatcher``'s compiled code for ``argtypes`` (numba types), compiled or loaded
    from numba's cache first."""
    argtypes = tuple(argtypes)
    dispatcher.compile(argtypes)
    result = dispatcher.overloads[argtypes]
    return result.library.get_pointer_to_function(result.fndesc.llvm_func_name)


def signature(prob, rest):
    """The argument types ``by_address`` compiles its callee for: the first argument's type, then ``rest``."""
    return (numba.typeof(prob) if not isinstance(prob, types.Type) else prob,) + tuple(rest)


def by_address(dispatcher, rest, slot):
    """A compiled function (a numba intrinsic) taking what ``dispatcher`` takes, (prob, *rest), that
    calls ``dispatcher``'s code at the address ``prob.calls[slot]``; ``rest``: the numba types of the
    arguments after ``prob`` (the caller's are converted to them)."""
    rest = tuple(rest)

    def typed(prob):
        argtypes = (prob,) + rest
        dispatcher.compile(argtypes)  # the callee's return type (and its code, compiled once)
        restype = dispatcher.overloads[argtypes].signature.return_type
        field = prob.fields.index("calls")

        def codegen(context, builder, sig, values):
            calls = context.make_array(prob.types[field])(context, builder,
                                                          value=builder.extract_value(values[0], field))
            where = builder.load(builder.gep(calls.data, [ir.Constant(ir.IntType(64), slot)]))
            function = context.call_conv.get_function_type(restype, argtypes)
            pointer = builder.inttoptr(where, function.as_pointer())
            status, result = context.call_conv.call_function(builder, pointer, restype, argtypes, values)
            with cgutils.if_unlikely(builder, status.is_error):
                context.call_conv.return_status_propagate(builder, status)
            return result

        return restype(*argtypes), codegen

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
