"""The finite-element core: bases of a mesh, weak forms, vectorised assembly, loads,
supports, the assembled and supported system with its reactions and equilibrium check,
stress recovery and the result fields.  Nothing here knows a crankshaft: the throw's
unit cases are in ``fe.throw``, the whole shaft's in ``fe.shaft``."""
