"""Time integration: the integrator contract (``integrator``), the schemes (``schemes``) and their one
registry (``registry``), the Newton policy of a step written once (``policy``) with its Python ops
(``python_ops``), the step control (``step_control``), the junction groups (``junctions``) and the energy
bookkeeping of a line between states (``energy``)."""
