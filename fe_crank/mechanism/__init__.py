"""The mechanism stage: slider-crank kinematics, gas pressure, engine dynamics over the
cycle and the cycles at the overspeed.

``kinematics`` (piston motion, exact and harmonic), ``slider_crank`` (one cylinder's
exact dynamics), ``gas`` (cylinder-pressure tables and models), ``dynamics`` (forces and
torques of the whole engine over one cycle: ``analyse(engine, operating) ->
DynamicsResult``), ``cycles`` (the operating cycle with the overspeed cycles:
``engine_cycles(engine, operating) -> EngineCycles``).
"""
