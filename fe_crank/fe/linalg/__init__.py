"""The linear algebra of the FE stage: which solver (``choice``) and a stiffness matrix
factorised once and solved for many load cases, in core or out of core
(``factorise``).  The mirror-symmetric solve, which needs the mesh's mirror and the
supports, is ``fe.core.symmetric``."""
