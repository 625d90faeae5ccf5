"""Helpers of the render-level shading tests (tests/render/test_shading_*.py): meshes and the
per-pixel geometry their closed forms need."""

import numpy as np


def quad_mesh(half, height=0.0):
    """A square floor of side 2 half at y = height facing +y: (vertices (4, 3), triangles (2, 3))."""
    v = np.array([[-half, height, -half], [half, height, -half], [half, height, half], [-half, height, half]], float)
    return v, np.array([[0, 2, 1], [0, 3, 2]])


def floor_points(origin, direction, half, height=0.0):
    """Where rays (origin (3,), directions (N, 3)) meet the floor square y = height, |x|, |z| <= half:
    (points (N, 3), hit mask (N,))."""
    d = np.atleast_2d(direction)
    with np.errstate(divide="ignore", invalid="ignore"):
        t = (height - origin[1]) / d[:, 1]
    p = origin[None, :] + t[:, None] * d
    hit = (t > 0) & (np.abs(p[:, 0]) <= half) & (np.abs(p[:, 2]) <= half)
    return p, hit


def pixel_grid_mean(camera, k, intersect, radiance):
    """The mean over a k x k grid inside each pixel of radiance(points) where intersect(origin,
    directions) -> (points, mask) hits: (image (H, W), mask of pixels fully on the surface)."""
    h, w = camera.height, camera.width
    image = np.zeros((h, w))
    full = np.ones((h, w), bool)
    offsets = (np.arange(k) + 0.5) / k
    for j in range(h):
        for i in range(w):
            dirs = []
            for dv in offsets:
                for du in offsets:
                    origin, d = camera.ray(i + du, j + dv)
                    dirs.append(d)
            points, hit = intersect(np.asarray(origin), np.array(dirs))
            full[j, i] = hit.all()
            if hit.any():
                image[j, i] = np.where(hit, radiance(np.where(hit[:, None], points, 0.0)), 0.0).mean()
    return image, full


FALSE_ALARM = 1e-3  # chance that a correct renderer fails a whole-image check (Bonferroni over pixels)


def check_against(renders, expected, mask, allowance=0.0):
    """Per-pixel Student-t test of seed renders (S, H, W) against expected (H, W) on mask: each
    pixel's mean must lie within t_{1 - a/2}(S - 1) standard errors (estimated from the S seeds'
    spread) plus `allowance` (absolute, per pixel), a = FALSE_ALARM / (number of pixels). Returns
    (worst |mean - expected| / stderr, the bound in stderr units, the image sum's relative error
    and that error's standard error from the seeds' sums)."""
    from scipy import stats

    seeds = renders.shape[0]
    mean = renders.mean(0)
    stderr = renders.std(0, ddof=1) / np.sqrt(seeds)
    count = int(mask.sum())
    sigmas = float(stats.t.ppf(1.0 - FALSE_ALARM / (2.0 * count), seeds - 1))
    excess = np.abs(mean - expected) - allowance
    z = np.where(mask, np.maximum(excess, 0.0) / np.maximum(stderr, 1e-12), 0.0)
    sums = renders[:, mask].sum(1) / expected[mask].sum()
    relative = float(abs(sums.mean() - 1.0))
    relative_stderr = float(sums.std(ddof=1) / np.sqrt(seeds))
    return float(z.max()), sigmas, relative, relative_stderr


def box_mesh(lo, hi, inward=False):
    """An axis-aligned box [lo, hi] (3,) as (vertices (8, 3), triangles (12, 3)), every triangle's
    counter-clockwise front facing out of the box (inward=True: into it)."""
    lo, hi = np.asarray(lo, float), np.asarray(hi, float)
    corners = np.array(
        [[(lo, hi)[x][0], (lo, hi)[y][1], (lo, hi)[z][2]] for x in (0, 1) for y in (0, 1) for z in (0, 1)]
    )
    centre = 0.5 * (lo + hi)
    triangles = []
    for axis in range(3):
        others = [a for a in range(3) if a != axis]
        for side in (0, 1):
            quad = []
            for a, b in ((0, 0), (1, 0), (1, 1), (0, 1)):
                bits = [0, 0, 0]
                bits[axis], bits[others[0]], bits[others[1]] = side, a, b
                quad.append(bits[0] * 4 + bits[1] * 2 + bits[2])
            p = corners[quad]
            outward = np.cross(p[1] - p[0], p[2] - p[0]) @ (p.mean(0) - centre) > 0
            if outward == inward:
                quad = quad[::-1]
            triangles += [[quad[0], quad[1], quad[2]], [quad[0], quad[2], quad[3]]]
    return corners, np.array(triangles)


def fresnel_dielectric(cos_i, eta):
    """Unpolarised Fresnel reflectance (Born & Wolf; SHADING.md section 1), eta = eta_t / eta_i,
    cos_i > 0 on the incident side; 1 under total internal reflection."""
    sin2_t = (1.0 - cos_i**2) / eta**2
    if sin2_t >= 1.0:
        return 1.0
    cos_t = np.sqrt(1.0 - sin2_t)
    rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t)
    rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t)
    return 0.5 * (rs**2 + rp**2)
