"""The model a scene describes: line types and lines (``line``), the scene's data classes and defaults
(``scene``), the built-in scenes (``builtin``), networks of points and bodies (``network``) and
prescribed motions (``motion``). Data only: no FEM, no solver."""
