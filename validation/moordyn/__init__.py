"""cablefem side by side with MoorDyn-C (PyPI ``moordyn``) on the same MoorDyn input files.

``peer`` runs a MoorDyn file with prescribed motions of its coupled points (reused by the
work-precision study); ``switches`` holds the cablefem variants that switch a physics
difference to MoorDyn's model (vertical seabed contact, hydrodynamics per unstretched length);
``run`` is the study (``python -m validation.moordyn.run [--fast] [--out DIR]``).
"""
