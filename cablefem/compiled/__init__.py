"""The compiled face (numba): the element loop over the load catalog (``kernels``), its evaluator from
Python (``evaluator``), the banded LU (``banded``), the Newton policy's compiled ops (``steps``) with the
seabed projected in the loop (``seabed``), the packing of a group of strings into their problem
(``problem``), the compile notice (``progress``) and the on-disk kernel cache (``cache``)."""
