"""One node group over the cycle: which nodes are assessed and their unit-case stresses
(``nodes``), a group's static, overspeed and fatigue results (``assessment``), and its
worst values found without every node's history: bounds of a node's stress path
(``bounds``), the largest von Mises stress (``peak``) and each criterion's extreme over
the nodes that can hold it (``extremes``)."""
