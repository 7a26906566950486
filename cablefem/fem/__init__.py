"""The finite element discretisation of one line (scikit-fem): the mesh over unstretched arc length and
its bases (``discretisation``), the weak form's reference assembly (``forms``), and the discrete system
of a line with its loads, residual and tangent (``system``)."""
