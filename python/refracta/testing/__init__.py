"""Statistical test tools for users' own code: ``refracta.testing.chi2`` (goodness of fit of a
direction sampler against its density over the sphere)."""

from . import chi2

__all__ = ["chi2"]
