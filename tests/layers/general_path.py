"""The general Stroh path of surfwave.layered, forced for an isotropic stack (a reference for the isotropic path)."""
from __future__ import annotations

import surfwave
from surfwave.layers import solve


def layered_general(substrate, films, **kw):
    """surfwave.layered(substrate, films, **kw) on the general path (``solve.FAST_ISOTROPIC`` off for the call)."""
    try:
        solve.FAST_ISOTROPIC = False
        return surfwave.layered(substrate, films, **kw)
    finally:
        solve.FAST_ISOTROPIC = True
