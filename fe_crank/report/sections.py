"""Report sections built from stage outputs: (heading, builder) in page order.

A builder takes ``(folder, stage_out, options)``, writes its pictures into
``folder`` and returns HTML fragments, or an empty list when the stage it shows
did not run (the page header then carries the error that stopped it).
"""

from __future__ import annotations

BUILDERS: list = []
