"""Time integration: what a scheme is (``scheme``), the schemes (``bdf2``, ``generalized_alpha``) and
their one registry (``registry``), the integrator (``integrator``), the Newton policy and its one step
control written once (``policy``) with its Python ops (``python_ops``), groups of strings, a line
alone or those meeting at junctions (``group``), and the energy bookkeeping of a line between states
(``energy``)."""
