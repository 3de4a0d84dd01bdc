"""The hot-spot convergence study: the levels and their peaks (``levels``), the load sets
(``loads``), the study by zones round the hot spots (``zone``, ``zone_study``) and the
study's driver with its Richardson estimate (``convergence``; docs/fe.md)."""
