"""The rules the assessment applies, each with its own formulas and validity ranges:
IACS UR M53 (``m53``) and VDI 2230 Part 1 (``vdi2230``).  A rule takes SI numbers and
the FE results it needs; how a throw is assessed with it is ``fe_crank.assess``'s."""
