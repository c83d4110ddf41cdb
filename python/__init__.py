"""Archipelago: stickiness of islands around islands in area-preserving maps.

C. F. F. Karney, "Long-time correlations in the stochastic regime", Physica D 8 (1983) 360-380.
Every number comes from the C++ core (the same code as archipelago-cli and the GUI): the exact fixed-point map
N of appendix B, trapping runs (section 3), their statistics (f_t, P_t, C_tau, D: section 3, appendix A),
portraits (fig. 1), periodic orbits and island chains, the stable and unstable manifolds of hyperbolic orbits and the
turnstile flux through them (manifold(), flux()), the flux through a cantorus (cantorus()).  Lengths and times are in steps of the map.

    import archipelago as ap
    run = ap.start(K=0.1, T=10000, M=16)
    run.advance(threads=2)
    s = run.statistics()
"""
from ._archipelago import *  # noqa: F401,F403
from ._archipelago import __version__  # noqa: F401
