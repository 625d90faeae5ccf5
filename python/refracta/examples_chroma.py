"""The colour noise of spectral renders through dispersive air, and a filter for it (the demo's
green flash frames).

Why the frames are mottled: through air that disperses, every sample keeps its hero wavelength
only (refracta.render, spectral=True: the other three are terminated; Wilkie et al. 2014, sect. 4),
drawn uniformly over 360-830 nm. A sample's colour is then that of one spectral line, and the sun
seen through ~38 air masses is so red (at 450 nm 0.2 % of its radiance at 700 nm) that its
luminance estimate per sample has a relative standard deviation of ~3.3 (measured on the disc of
the demo's second frame: 3.3 at 1 spp, 1.19 at 8 spp, as 1/sqrt(spp)). Open Image Denoise takes
the luminance noise out but leaves its chroma in blotches of a few pixels (the normalised rgb of
the disc varies by 0.10 after it at 1 spp, still 0.06 at 8 spp), and the display, which clips the
disc to its own hue, shows exactly that chroma. Eight times the samples would cost ~8 x 55 s of
CPU and still leave it; averaging the colour over many neighbouring pixels of the same brightness
removes it: chroma_filter.
"""

from __future__ import annotations

import numpy as np

# Rec. 709 / linear sRGB luminance weights (the Y row of the sRGB-to-XYZ matrix).
LUMINANCE = np.array([0.2126, 0.7152, 0.0722])


def _gaussian_blur(planes: np.ndarray, sigma: float) -> np.ndarray:
    """Blur (k, H, W) planes by a Gaussian of `sigma` [px] over H and W, through the FFT of the
    planes zero-padded by 3 sigma (no wrap-around; the edges darken, which the weights' own blur
    divides out)."""
    k, h, w = planes.shape
    pad = int(np.ceil(3.0 * sigma))
    shape = (h + 2 * pad, w + 2 * pad)
    fy, fx = np.fft.fftfreq(shape[0]), np.fft.rfftfreq(shape[1])
    kernel = np.exp(-2.0 * (np.pi * sigma) ** 2 * (fy[:, None] ** 2 + fx[None, :] ** 2))
    padded = np.zeros((k, *shape))
    padded[:, pad : pad + h, pad : pad + w] = planes
    blurred = np.fft.irfft2(np.fft.rfft2(padded) * kernel, s=shape)
    return blurred[:, pad : pad + h, pad : pad + w]


def _upsample(small: np.ndarray, factor: int, h: int, w: int) -> np.ndarray:
    """Bilinear interpolation of (k, h / factor, w / factor) cell values (each the mean of a
    factor x factor block) back to (k, h, w) pixels."""

    def axis(n, cells):
        centre = (np.arange(n) + 0.5) / factor - 0.5  # pixel centres in cell units
        lo = np.clip(np.floor(centre).astype(int), 0, cells - 1)
        hi = np.minimum(lo + 1, cells - 1)
        return lo, hi, np.clip(centre - lo, 0.0, 1.0)

    y0, y1, ty = axis(h, small.shape[1])
    x0, x1, tx = axis(w, small.shape[2])
    rows = small[:, y0] * (1 - ty)[None, :, None] + small[:, y1] * ty[None, :, None]
    return rows[:, :, x0] * (1 - tx)[None, None, :] + rows[:, :, x1] * tx[None, None, :]


def _blur(planes: np.ndarray, sigma: float) -> np.ndarray:
    """_gaussian_blur of (k, H, W) planes on a grid `factor` = sigma // 4 times coarser (block
    means, blurred by sigma / factor cells, interpolated back): the bilateral grid's sampling
    (Chen, Paris & Durand 2007), at sigma / factor >= 4 cells the error of a few per cent of the
    kernel's own detail -- 36x cheaper at sigma = 24 px."""
    factor = max(1, int(sigma // 4))
    if factor == 1:
        return _gaussian_blur(planes, sigma)
    k, h, w = planes.shape
    cells = (-(-h // factor), -(-w // factor))
    padded = np.zeros((k, cells[0] * factor, cells[1] * factor))
    padded[:, :h, :w] = planes
    small = padded.reshape(k, cells[0], factor, cells[1], factor).mean(axis=(2, 4))
    return _upsample(_gaussian_blur(small, sigma / factor), factor, h, w)


# The green flash frames' filter (tried on crops of the demo's first and second frames at 1 spp,
# against 8 spp): a sample's green has a relative standard deviation of ~3 on the reddened disc;
# averaging over 8 px (~800 pixels) left the chroma's green varying by 12 % (rel. std) across a
# 200 px crop of frame 1's disc, 24 px (~7000 pixels) 5 %, the rim keeping its colours. 0.3 in
# ln Y keeps the rim, where ln Y changes by ~2.5 a pixel.
CHROMA_SIGMA = 24.0  # [px]
CHROMA_RANGE = 0.3  # in ln Y


def chroma_filter(
    noisy: np.ndarray, luminance: np.ndarray, sigma: float = CHROMA_SIGMA, range_sigma: float = CHROMA_RANGE
):
    """The colour of `noisy` (H, W, 3) linear RGB averaged over the pixels around each one (a
    Gaussian of `sigma` [px]) whose log luminance is near its own (a Gaussian of `range_sigma` in
    ln Y), times `luminance` (H, W) over that average's own luminance: a joint (cross) bilateral
    filter of the colour, guided by a denoised luminance (Eisemann & Durand 2004, "Flash
    photography enhancement via intrinsic relighting"; Petschnigg et al. 2004), computed as
    Durand & Dorsey's piecewise-linear bilateral (2002, "Fast bilateral filtering for the display
    of high-dynamic-range images"): one blurred slice per level of ln Y, `range_sigma` apart, each
    pixel interpolated between the two slices around its own level.

    Colour noise goes down as the square root of the pixels averaged (~4 pi sigma^2 on a flat
    disc: ~7000 at 24 px); edges in luminance -- the disc's outline, its green rim, where ln Y
    changes by ~2.5 a pixel -- are not crossed: along the rim the pixels of the same brightness
    are the rim's own. `luminance` should be smooth (Open Image Denoise's output): its noise would
    split the neighbours into brightness classes at random. (Blurring it by 0.5-1.5 px first, to
    part it further from each pixel's own sample, changed the rim's colour error against the 8 spp
    frame by under 5 %, and lets colour cross a sharp edge by a pixel: not done.)"""
    noisy = np.asarray(noisy, dtype=np.float64)
    luminance = np.asarray(luminance, dtype=np.float64)
    if noisy.ndim != 3 or noisy.shape[2] != 3 or luminance.shape != noisy.shape[:2]:
        raise ValueError(
            f"chroma_filter: noisy must be (H, W, 3) and luminance (H, W) (got {noisy.shape}, {luminance.shape})"
        )
    if not (np.isfinite(noisy).all() and np.isfinite(luminance).all()):
        raise ValueError("chroma_filter: noisy and luminance must be finite (got NaN or inf)")
    if not sigma > 0 or not range_sigma > 0:
        raise ValueError(f"chroma_filter: sigma and range_sigma must be > 0 (got {sigma}, {range_sigma})")
    positive = luminance[luminance > 0]
    floor = 1e-6 * positive.max() if positive.size else 1.0  # ln of black pixels: 6 decades below the brightest
    guide = np.log(np.maximum(luminance, floor))
    levels = np.arange(guide.min(), guide.max() + range_sigma, range_sigma)
    colour = np.moveaxis(noisy, 2, 0)
    filtered = np.zeros_like(colour)
    weight_sum = np.zeros(guide.shape)
    for level in levels:
        hat = np.clip(1.0 - np.abs(guide - level) / range_sigma, 0.0, 1.0)  # this slice's share of each pixel
        if not hat.any():
            continue
        w = np.exp(-0.5 * ((guide - level) / range_sigma) ** 2)
        blurred = _blur(np.concatenate([colour * w, w[None]]), sigma)
        filtered += hat * blurred[:3] / np.maximum(blurred[3], 1e-12)
        weight_sum += hat
    filtered = np.moveaxis(filtered / np.maximum(weight_sum, 1e-12), 0, 2)
    own = filtered @ LUMINANCE
    scale = np.where(own > 0, luminance / np.where(own > 0, own, 1.0), 0.0)
    return (filtered * scale[..., None]).astype(np.float32)


def gamut_map(image: np.ndarray) -> np.ndarray:
    """Linear sRGB (H, W, 3) brought inside the gamut's lower boundary (no negative channel) with
    its luminance kept: each pixel with a negative channel is desaturated toward the grey of its
    own luminance Y, c' = Y + t (c - Y), t the largest in [0, 1] leaving every channel >= 0
    (t = Y / (Y - min c)); in-gamut pixels are unchanged, and pixels of Y <= 0 go to black.

    Why: the green flash's spectral light lies outside the sRGB primaries' triangle -- the last
    gleam's light at 520 nm is (-1.30, 1.79, -0.08) x Y in linear sRGB -- and clipping the negative
    channels to 0, as the frames did, adds luminance (28 % at 520 nm) and moves the hue toward the
    nearest primary; desaturating toward the same
    luminance keeps the brightness the physics gives and the hue line (CIE's constant-luminance
    gamut mapping; as a camera's processing maps the spectral colours it records into its output
    space). Float32 out."""
    image = np.asarray(image, dtype=np.float64)
    if image.ndim != 3 or image.shape[2] != 3:
        raise ValueError(f"gamut_map: image must be (H, W, 3) (got {image.shape})")
    if not np.isfinite(image).all():
        raise ValueError("gamut_map: image must be finite (radiance)")
    y = image @ LUMINANCE
    lowest = image.min(axis=2)
    t = np.where(lowest < 0.0, np.clip(y / np.maximum(y - lowest, 1e-300), 0.0, 1.0), 1.0)
    mapped = y[..., None] + t[..., None] * (image - y[..., None])
    return np.maximum(mapped, 0.0).astype(np.float32)  # the last max: rounding and Y <= 0 pixels
