"""Lines of the axial laws of ``cablefem.loads.rope`` for the tests (tests/test_rope.py, test_catalog.py):
a taut polyester line with each law, its history set to a state a run could be in."""

import numpy as np

from cablefem.fem.system import LineSystem
from cablefem.geometry import Horizontal
from cablefem.model.axial import AxialLaw, Curve, Syrope
from cablefem.model.line import Line, LineType, Segment
from cablefem.model.scene import Contact, Environment

#: a polyester-like strain-tension table (rows away from the test states' strains of 1.3-2.7 %)
TABLE = Curve.from_rows([0.0, 0.004, 0.011, 0.031, 0.05], [0.0, 3.0e5, 1.0e6, 3.6e6, 7.0e6], "EA")
#: MoorDyn's tests/Mooring/syrope/owc.dat, every other row
OWC = Curve.from_rows([0.0, 4.13793e-03, 8.27586e-03, 1.24138e-02, 1.65517e-02, 2.06897e-02, 2.48276e-02,
                       2.89655e-02, 3.31034e-02, 3.72414e-02, 4.13793e-02, 4.55172e-02, 4.96552e-02, 5.37931e-02,
                       5.79310e-02, 6.0e-02],
                      [0.0, 3.30952e+05, 6.16510e+05, 8.66556e+05, 1.09097e+06, 1.29964e+06, 1.50245e+06,
                       1.70927e+06, 1.93000e+06, 2.17450e+06, 2.45267e+06, 2.77439e+06, 3.14954e+06, 3.58800e+06,
                       4.09965e+06, 4.38601e+06], "EA")
LAWS = {
    "table": AxialLaw("table", TABLE, damping=2.0e5),
    "damping_table": AxialLaw("table", TABLE, damping_curve=Curve.from_rows(
        [0.002, 0.02, 0.2], [2.0e3, 1.2e4, 5.0e4], "BA", "strain_rate", signed=True)),
    "viscoelastic": AxialLaw("viscoelastic", static_EA=1.2e8, dynamic_EA=1.6e8, damping=4.0e8, dynamic_damping=2.0e6),
    "load_dependent": AxialLaw("viscoelastic", static_EA=1.2e8, dynamic_EA=1.4e8, dynamic_slope=9.0,
                               damping=4.0e8, dynamic_damping=2.0e6),
    "syrope": AxialLaw("syrope", OWC, dynamic_EA=1.53e8, dynamic_slope=23.12, damping=5.0e10, dynamic_damping=1.0e5,
                       syrope=Syrope("linear", 1.25e8, 0.0)),
    "syrope_exp": AxialLaw("syrope", OWC, dynamic_EA=1.53e8, dynamic_slope=23.12, damping=5.0e9,
                           dynamic_damping=1.0e6, syrope=Syrope("exp", 0.2, 1.5)),
}
#: SYROPE's initial condition (MoorDyn's syrope tests: Tmax0 = 0.16 MBL, Tmean0)
INITIAL = (1.3886e6, 4.339e5)


def rope_type(kind, slack=False):
    """A 0.2 m polyester line type of law ``kind`` (``LAWS``), MoorDyn-C's slack law with ``slack``."""
    law = LAWS[kind]
    return LineType(f"rope-{kind}", 0.2, 40.0, law.reference_EA, Cd_normal=1.6, Cd_tangential=0.1, Ca_normal=1.0,
                    damping_when_slack=slack, axial=law)


def rope_system(kind, order, slack=False, rng=None):
    """A line of 6 elements of law ``kind`` (``order``: 1-3, or "hermite": Hermite elements) between
    prescribed ends over a 100 m flat seabed, its
    slow strain (viscoelastic, SYROPE) set to 0.4-0.8 % and SYROPE's peak to its initial condition."""
    line_type = rope_type(kind, slack)
    initial = INITIAL if line_type.axial.kind == "syrope" else None
    kind_of_element = {"element": "hermite"} if order == "hermite" else {"order": order}  # order "hermite": Hermite
    line = Line("rope", [0.0, 0.0, -50.0], [101.8, 0.0, -50.0], [Segment(line_type, 100.0, 6, initial)],
                **kind_of_element)
    system = LineSystem(line, Horizontal(100.0), Contact(), Environment(), dynamic=True)
    rng = rng or np.random.default_rng(5)
    old, new = system.history["reduced"]
    if line_type.axial.kind != "table":
        old["rope"]["slow"] = rng.uniform(0.004, 0.008, old.shape)
        old["rope"]["peak"] = INITIAL[0]
        new[...] = old
    return system


def rope_state(system, rng):
    """X of a wavy taut line (strains 1.3-2.7 %, away from the table's rows), nodal velocities of
    ~0.05 m/s and random accelerations: (X, V, A)."""
    X = system.fem.interpolate(lambda s: np.column_stack([s * 1.02 + 0.05 * np.sin(s / 10.0), 0.2 * np.cos(s / 7.0),
                                                          -50.0 + 0.5 * np.sin(s / 13.0)]))
    V = rng.standard_normal(X.shape) * 0.05
    A = rng.standard_normal(X.shape)
    return X, V, A
