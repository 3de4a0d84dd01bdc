"""IACS UR M53 "Calculation of crankshafts for I.C. engines", Rev.1 (Dec 2004): the
nominal stresses, fatigue strength and acceptability of the fillets (``calculation``),
what the rule takes from the machine and the material (``basis``), the empirical SCFs
and their validity range (``scf_empirical``), the crankpin oil-bore outlet
(``oil_bore``), nominal moments rod by rod (``rods``), and the SCF mode of App. III:
its FE load cases and stress measures (``fe_cases``), the web mesh it demands
(``web_mesh``), the SCFs from them (``scf_mode``) on a mesh refined until the appendix
accepts it (``scf_refine``)."""
