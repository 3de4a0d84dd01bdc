"""The counterweight study: candidates of balance rate and placement screened on the
whole shaft's condensed unit cases (docs/study.md)."""
