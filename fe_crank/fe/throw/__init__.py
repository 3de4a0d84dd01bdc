"""One crank throw's FE model: its statically determinate support, the crankpin cases by
direction and by rod place, the unit load cases solved on one factorisation, the node
groups it is assessed at and the peak stress on its named surfaces."""
