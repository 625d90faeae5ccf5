"""refracta.denoise: Intel Open Image Denoise (PyPI ``pyoidn``) on refracta's linear HDR renders."""

from __future__ import annotations

import numpy as np

FLOAT32_MAX = float(np.finfo(np.float32).max)  # Open Image Denoise works in float32
# Outside [TINY_RADIANCE, HUGE_RADIANCE] at its largest value Open Image Denoise is given the image
# scaled to 1 (1e30 was still fine; at 1e-10 its output was all zeros, with guides up to 700x the
# image's largest value: a trial; 1e-8 was still exact).
HUGE_RADIANCE = 1e20
TINY_RADIANCE = 1e-6


def _channels(name: str, array, shape=None, lo: float = 0.0, hi: float = np.inf) -> np.ndarray:
    """`array` as a C-contiguous float32 (H, W, 3) within [lo, hi]; ValueError naming it otherwise."""
    values = np.asarray(array)
    if array is None or values.dtype.kind not in "biuf":
        shown = "None" if array is None else f"dtype {values.dtype}"
        raise ValueError(f"denoise: {name} must be an (H, W, 3) array of real numbers (got {shown})")
    if values.dtype.kind != "f":  # an 8-bit picture came back as radiance 111-143
        raise ValueError(
            f"denoise: {name} must be floats, linear (got dtype {values.dtype}: a display-encoded picture? "
            "refracta.io.read_image(path, linear=True) decodes one)"
        )
    if values.ndim != 3 or values.shape[2] != 3 or values.shape[0] < 1 or values.shape[1] < 1:
        raise ValueError(f"denoise: {name} must have shape (H, W, 3), H and W >= 1 (got {values.shape})")
    if shape is not None and values.shape != shape:
        raise ValueError(f"denoise: {name} must have the image's shape {shape} (got {values.shape})")
    if not np.all(np.isfinite(values)):
        raise ValueError(f"denoise: {name} must be finite (it has NaN or inf)")
    if name == "image" and values.min() < 0.0 and values.max() <= hi:
        raise ValueError(
            f"denoise: image must be >= 0 (got values down to {values.min():g}): a spectral render's colours "
            "outside sRGB's gamut come out negative; denoise np.maximum(image, 0), as render(denoise=True) does"
        )
    if values.min() < lo or values.max() > hi:
        raise ValueError(f"denoise: {name} must lie in [{lo:g}, {hi:g}] (got [{values.min():g}, {values.max():g}])")
    return np.ascontiguousarray(values, dtype=np.float32)


# The guided filter after Open Image Denoise (denoise's `guided`, off by default; render's with
# guide_spp above spp): a local linear regression of the
# denoised colour on the six guide channels (albedo, normal) in each (2 r + 1)^2 window, as He et
# al.'s guided filter (2013, "Guided Image Filtering", IEEE TPAMI 35(6), eqs. 13-16 with a colour
# guide; as a Monte Carlo denoiser: Bauszat et al. 2011, "Guided Image Filtering for Interactive
# High-quality Global Illumination"). Where a window spans an edge between surfaces, the colour is
# close to linear in the guides' blend of them, so each pixel takes the colour its guides' coverage
# of the surfaces says, not the coverage its own samples drew (Open Image Denoise keeps that
# sub-pixel coverage noise as detail: benchmarks/bench_denoise.py); in a window of one surface the
# guides are constant and the colour is averaged over it (unbiased). Measured on the demo scenes'
# crops (16 spp 'direct' against 1024 spp): radius 1 and ridge 1e-5 lowered the relative MSE after
# Open Image Denoise on all four (hot road 2.03x -> 2.77x, Fata Morgana 2.75x -> 3.59x); radius 2
# blurs lighting that is not in the guides (2.41x, 3.01x), a ridge of 1e-3 (weighting the guides'
# differences less than the colour's noise) undoes it (0.86x on the hot road).
GUIDED_RADIUS = 1  # [px]: a 3 x 3 window
GUIDED_RIDGE = 1e-5  # added to the guides' covariance: albedo and normal channels vary by 0.01-1 across edges


# Open Image Denoise's output drifts at the image's edges: a constant 0.5 image came back up to
# 17 % off at its corners at 24 px, 4-8 % along the borders of 64-128 px ones (with or without
# albedo and normal). Denoising the image mirrored BORDER_MARGIN pixels beyond each edge (albedo and
# normal alike; numpy's 'reflect', the edge pixel not repeated) and cropping it back leaves a constant
# image within 0.26 % (8 px: 0.37 %, 32 px: 0.18 %); it costs the margin's pixels (a 640 x 320
# image 16 % more, a 4K one 2.5 %). Measured on a path-traced sphere and ground (96 x 64, 4 spp,
# seeds 1-4, relative MSE against 256 spp): the 6 px border band 0.00154 -> 0.00097 (colour only),
# 0.00094 -> 0.00080 (with albedo and normal), the inside unchanged or lower (0.00263 -> 0.00225,
# 0.00262 -> 0.00260); the hot road at 128 x 48, 16 spp with guides (one seed): 0.00310 -> 0.00289
# whole, a 24 x 24 crop 0.0120 -> 0.0082. Colour alone, single seeds vary either way (sphere seed 0
# whole image 0.00197 -> 0.00248, hot road 0.00621 -> 0.00705, its 24 x 24 crop 0.0198 -> 0.0172).
BORDER_MARGIN = 16  # [px]


def _mirrored(values: np.ndarray | None, margin: int) -> np.ndarray | None:
    """`values` (H, W, 3) mirrored `margin` pixels beyond each edge, C-contiguous float32."""
    if values is None:
        return None
    padded = np.pad(values, [(margin, margin), (margin, margin), (0, 0)], mode="reflect")
    return np.ascontiguousarray(padded, dtype=np.float32)


def _box_mean(values: np.ndarray, radius: int) -> np.ndarray:
    """Mean of `values` (H, W, ...) over the (2 radius + 1)^2 window around each pixel, the image
    mirrored at its borders."""
    width = 2 * radius + 1
    padded = np.pad(values, [(radius, radius), (radius, radius)] + [(0, 0)] * (values.ndim - 2), mode="symmetric")
    sums = np.cumsum(np.cumsum(padded, axis=0), axis=1)
    sums = np.pad(sums, [(1, 0), (1, 0)] + [(0, 0)] * (values.ndim - 2))
    window = sums[width:, width:] - sums[:-width, width:] - sums[width:, :-width] + sums[:-width, :-width]
    return window / (width * width)


def _guided_filter(color: np.ndarray, guide: np.ndarray, radius: int = GUIDED_RADIUS, ridge: float = GUIDED_RIDGE):
    """He et al.'s guided filter of `color` (H, W, 3) by `guide` (H, W, K), float64, in bands of
    rows (the K x K systems of a whole 4K image would take gigabytes)."""
    height, k = color.shape[0], guide.shape[2]
    band, halo = 64, 2 * radius  # the coefficients' own window mean needs radius more rows
    out = np.empty_like(color)
    for top in range(0, height, band):
        lo, hi = max(0, top - halo), min(height, top + band + halo)
        g, p = guide[lo:hi], color[lo:hi]
        mean_g, mean_p = _box_mean(g, radius), _box_mean(p, radius)
        cov_gg = _box_mean(g[..., :, None] * g[..., None, :], radius) - mean_g[..., :, None] * mean_g[..., None, :]
        cov_gp = _box_mean(g[..., :, None] * p[..., None, :], radius) - mean_g[..., :, None] * mean_p[..., None, :]
        a = np.linalg.solve(cov_gg + ridge * np.eye(k), cov_gp)  # (h, W, K, 3)
        b = mean_p - np.einsum("hwk,hwkc->hwc", mean_g, a)
        filtered = np.einsum("hwk,hwkc->hwc", g, _box_mean(a, radius)) + _box_mean(b, radius)
        out[top : min(height, top + band)] = filtered[top - lo : top - lo + min(band, height - top)]
    return out


def denoise(
    image, albedo=None, normal=None, *, quality: str = "high", clean_aux: bool = True, guided: bool = False
) -> np.ndarray:
    """A Monte Carlo render with its noise removed by Intel Open Image Denoise's ``RT`` filter.

    image: (H, W, 3) linear radiance (refracta.render's output; HDR, >= 0; floats). A bright feature
    smaller than a pixel that the guides do not show (a distant lamp, a glint) is taken for noise
    and loses most of its light, even converged (a lamp 1.5 % of a pixel kept 13 % at 1024 spp).
    albedo: the optional (H, W, 3) reflectance of the first non-specular surface each pixel sees, in
    [0, 1]; normal: its (H, W, 3) unit normal (needs albedo). Both sharpen edges and textures the
    noise would blur. quality: 'high', 'balanced' or 'fast'. clean_aux: the albedo and normal are
    noise-free, as render(aovs=...) gives them (a fixed-sample directional albedo; only the pixel's
    own antialiasing averages them), so Open Image Denoise trusts them fully (measured on the hot
    road, 160 x 60, 16 spp: relative MSE against 1024 spp 3.3x lower with False, 4.1x with True);
    False for albedo and normal that carry Monte Carlo noise. guided: with clean albedo and normal,
    Open Image Denoise's output is then regressed on them in 3 x 3 windows (a guided filter, He et
    al. 2013; GUIDED_RADIUS, GUIDED_RIDGE): edges between surfaces take the coverage the guides
    give, not the one the pixel's own samples drew, which Open Image Denoise keeps as detail
    (relative MSE on the demo scenes' hardest crops, 16 spp 'direct' against 4096: hot road 2.0x ->
    2.8x below the noisy image's, Fata Morgana 1.95x -> 2.1x; with guides of more samples than the
    image, render(guide_spp=64): 5.7x and 2.6x; benchmarks/bench_denoise.py). Off by default: it
    also smooths lighting edges the guides do not show where they meet an edge the guides do show --
    the shadows at the feet of thin posts on a lit ground, 48 x 32 px, 16 spp: relative MSE 1.3x
    below the noisy image's with Open Image Denoise alone, 0.5x (worse than noisy) guided. Negative
    results of the regression are clipped to 0; pixels whose normal is 0 (no surface met) keep Open
    Image Denoise's output. Returns float32 (H, W, 3).

    The image (and its guides) is denoised mirrored BORDER_MARGIN pixels beyond its edges and
    cropped back, so its borders are denoised as its middle is (a constant image stays within
    0.5 %; Open Image Denoise alone moved its corners by up to 17 % at 24 px, 4 % at 64 px).

    Measured: a diffuse sphere and ground under the physical sky, 4 spp path traced, relative MSE
    against 256 spp falls about 15x (tests/render/test_denoise.py).
    """
    try:
        import pyoidn
    except ImportError as error:  # a dependency of refracta; missing only in a broken install
        raise ImportError("refracta.denoise needs Intel Open Image Denoise: pip install pyoidn") from error
    color = _channels("image", image, hi=FLOAT32_MAX)
    aux_albedo = None if albedo is None else _channels("albedo", albedo, color.shape, 0.0, 1.0)
    aux_normal = None if normal is None else _channels("normal", normal, color.shape, -1.0, 1.0)
    if aux_normal is not None and aux_albedo is None:
        raise ValueError("denoise: normal needs albedo as well (Open Image Denoise uses them together)")
    if quality not in ("high", "balanced", "fast"):
        raise ValueError(f"denoise: quality must be 'high', 'balanced' or 'fast' (got {quality!r})")
    if not isinstance(clean_aux, (bool, np.bool_)):
        raise ValueError(f"denoise: clean_aux must be True or False (got {clean_aux!r})")
    if not isinstance(guided, (bool, np.bool_)):
        raise ValueError(f"denoise: guided must be True or False (got {guided!r})")
    if guided and (aux_albedo is None or aux_normal is None or not clean_aux):
        raise ValueError(
            "denoise: guided=True regresses on the albedo and normal: give both, noise-free (clean_aux=True)"
        )
    margin = BORDER_MARGIN
    height, width = color.shape[:2]
    # A black image stays black (guided, Open Image Denoise put back light of ~1e-6).
    if not color.max() > 0.0:
        return np.zeros_like(color)
    # Open Image Denoise's own exposure estimate overflows for images near float32's limit (1e38
    # came back all zeros) and loses images of tiny values: those are denoised scaled to 1 at their
    # largest value, then scaled back (its output is scale-invariant; ordinary renders are left
    # exactly as they are).
    largest = float(color.max())
    scale = largest if largest > HUGE_RADIANCE or largest < TINY_RADIANCE else 1.0
    clean = np.asarray(
        pyoidn.denoise(
            _mirrored(color / np.float32(scale) if scale != 1.0 else color, margin),
            _mirrored(aux_albedo, margin),
            _mirrored(aux_normal, margin),
            hdr=True,
            quality=quality,
            clean_aux=bool(clean_aux) and aux_albedo is not None,
        ),
        dtype=np.float32,
    )
    clean = np.ascontiguousarray(clean[margin : margin + height, margin : margin + width])
    if scale != 1.0:
        clean *= np.float32(scale)
    if not np.all(np.isfinite(clean)):
        raise ValueError(
            f"denoise: Open Image Denoise's output overflowed float32 (image values up to {color.max():g}): "
            "scale the image down, denoise, and scale it back"
        )
    if not (guided and clean_aux and aux_albedo is not None and aux_normal is not None):
        return clean
    guide = np.concatenate([aux_albedo, aux_normal], axis=2).astype(np.float64)
    refined = np.maximum(_guided_filter(clean.astype(np.float64), guide), 0.0).astype(np.float32)
    # Where no sample met a surface (zero normal: the sky) the guides say nothing: a window of them
    # would only average Open Image Denoise's output (blurring the sun's rim by a pixel).
    sky = ~np.any(aux_normal, axis=2)
    refined[sky] = clean[sky]
    return refined
