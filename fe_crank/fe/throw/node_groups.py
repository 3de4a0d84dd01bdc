"""The node groups a throw is assessed at: fillets, oil bore, counterweights and their
junctions with the webs (mesh node numbers), the same for the per-throw model
(``assess.group.nodes``) and for each throw of the whole shaft (``fe.shaft.model`` keeps its
condensed fields there)."""

from __future__ import annotations

from typing import Literal

import numpy as np

#: what a node group is, from its name (``group_kind``): the shaft fillets, the oil-bore
#: outlet, another crankpin surface, a counterweight's transition fillet to the web, a
#: counterweight body, a counterweight's junction with its web
GroupKind = Literal[
    "crankpin_fillet", "journal_fillet", "oil_bore", "crankpin", "counterweight_fillet", "counterweight", "junction"
]
#: the name prefix of each kind, the longer first where one prefix starts another
_PREFIXES: tuple[GroupKind, ...] = (
    "crankpin_fillet",
    "journal_fillet",
    "oil_bore",
    "crankpin",
    "counterweight_fillet",
    "counterweight",
    "junction",
)

#: boundary groups assessed at their nodes; subdomains assessed with all their nodes
ASSESSED_BOUNDARIES = (
    "crankpin_fillet_1",
    "crankpin_fillet_2",
    "journal_fillet_1",
    "journal_fillet_2",
    "oil_bore",
    "counterweight_fillet_1",  # the counterweight-to-web transition fillets (geometry/cw_fillet.py)
    "counterweight_fillet_2",
)
COUNTERWEIGHTS = ("counterweight_1", "counterweight_2")


def group_kind(name: str) -> GroupKind | None:
    """The kind of the node group ``name`` (``crankpin_fillet_2`` -> ``crankpin_fillet``,
    ``counterweight_fillet_1`` -> ``counterweight_fillet``, ``junction_1`` -> ``junction``);
    None for a name of no kind."""
    for kind in _PREFIXES:
        if name.startswith(kind):
            return kind
    return None


def _element_nodes(basis, elements) -> np.ndarray:
    return np.unique(np.asarray(basis.element_dofs)[:, elements])


def node_groups(mesh, basis, *, bodies: bool = True) -> dict[str, np.ndarray]:
    """Mesh node numbers of every assessed group present in the mesh (``basis``: its scalar
    P2 basis): the fillet and oil-bore boundaries (all P2 nodes of their facets), each
    counterweight subdomain (``bodies``) and its junction with the web (nodes shared by
    the counterweight's and the web's elements)."""
    groups = {}
    for name in ASSESSED_BOUNDARIES:
        if name in (mesh.boundaries or {}):
            groups[name] = np.unique(basis.get_dofs(facets=mesh.boundaries[name]).all())
    subs = mesh.subdomains or {}
    for i, cw in enumerate(COUNTERWEIGHTS, start=1):
        if cw in subs:
            cw_nodes = _element_nodes(basis, subs[cw])
            if bodies:
                groups[cw] = cw_nodes
            web = f"web_{i}"
            if web in subs:
                junction = np.intersect1d(cw_nodes, _element_nodes(basis, subs[web]))
                if junction.size:
                    groups[f"junction_{i}"] = junction
    return groups
