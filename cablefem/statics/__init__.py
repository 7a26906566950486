"""Static equilibrium: Newton with its line search (``newton``), the strategies a solve tries in turn
(``solve``, ``continuation``), start shapes (``start_shape``) and the closed-form catenaries behind them
(``catenary``), the mesh fitted to the touchdown (``touchdown``), the pretension path in soil
(``pretension``), networks' coupling unknowns (``network``), and the statics of a whole scene
(``scene``)."""
