"""Order-independent transparency for one pixel's fragments (shared/MOMENTS.md 4).

composite(depths, alphas, colors, background=(0, 0, 0), method='exact'|'peel'|'wboit'|'mboit',
moments=4, kind='power', beta=0.25, bias=None, z_range=None, layers=None, weight='eq7') -> RGB.
depths are view depths (> 0), alphas in [0, 1], colors (K, 3) linear RGB (not premultiplied).
'exact' sorts (= depth peeling with enough layers); 'peel' keeps the `layers` nearest; 'wboit' is
McGuire & Bavoil 2013 with weight 'eq7' or 'eq9'; 'mboit' is moment-based OIT with 4, 6 or 8 power
moments (kind='power') or 2, 3 or 4 trigonometric moments (kind='trig', wrapping zone pi/10), a log
depth warp over z_range (default: the fragments' range), overestimation beta and the published
fp32 biases.
"""

from __future__ import annotations

import numpy as np

from refracta import _core


def composite(depths, alphas, colors, background=(0.0, 0.0, 0.0), method: str = "exact", moments: int = 4,
              kind: str = "power", beta: float = 0.25, bias: float | None = None,
              z_range: tuple[float, float] | None = None, layers: int | None = None,
              weight: str = "eq7", storage: str = "fp32") -> np.ndarray:
    """The pixel's colour after compositing its fragments over `background`. storage: MBOIT's
    moments in 'fp32' or the 16-bit ROV variant 'unorm16' (re-quantised after every fragment, in
    the given order; 4 power moments or trigonometric ones)."""
    colors = np.asarray(colors, dtype=np.float64).reshape(-1, 3)
    return _core._composite(np.asarray(depths, np.float64).ravel(), np.asarray(alphas, np.float64).ravel(),
                            colors, np.asarray(background, np.float64), method, int(moments), kind, float(beta),
                            bias, z_range, layers, weight, storage)
