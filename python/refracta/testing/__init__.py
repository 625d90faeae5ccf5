"""Statistical test tools for users' own code: ``refracta.testing.chi2`` (goodness of fit of a
direction sampler against its density over the sphere) and ``refracta.testing.tilts`` (the
first-order tilts of level paths through a turbulence layer)."""

from . import chi2, tilts

__all__ = ["chi2", "tilts"]
