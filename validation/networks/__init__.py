"""cablefem's mooring networks (issue 18) against MoorDyn-C (dynamics, coupled bodies) and MoorPy's
System (statics); ``python -m validation.networks.run``."""
