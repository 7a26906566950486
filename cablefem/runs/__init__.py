"""What ``cablefem static`` and ``cablefem run`` do from a scene to files: the time-domain run and its
writers (``run``), what a solve reports per line (``results``), a network's rows and frames
(``network_output``) and the static command's JSON (``static``)."""
