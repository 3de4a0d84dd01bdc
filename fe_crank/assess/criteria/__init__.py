"""The load case's criteria evaluated on the assessed throws: what each quantity is
found from (``finders``; a quantity over the speeds of the full-load curve is
``assess.speeds``'), the worse of both models (``models``), every criterion judged
once with the convergence study's factors (``judge``), the words a verdict line
carries (``qualifiers``) and the margin of a value against its limit (``verdict``)."""
