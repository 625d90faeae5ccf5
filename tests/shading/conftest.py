"""Shared helpers of the BSDF tests: directions in the local shading frame (z = normal)."""

import numpy as np


def direction(theta_deg, phi_deg=20.0, below=False):
    """Unit vector at polar angle theta from +z (from -z when below) and azimuth phi."""
    t, p = np.radians(theta_deg), np.radians(phi_deg)
    return np.array([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), (-1 if below else 1) * np.cos(t)])


def sphere_grid(n_theta=200, n_phi=400, hemisphere=False):
    """Midpoint quadrature over the sphere (or upper hemisphere): directions (M, 3), weights d omega (M,)."""
    top = np.pi / 2 if hemisphere else np.pi
    t = (np.arange(n_theta) + 0.5) * top / n_theta
    p = (np.arange(n_phi) + 0.5) * 2 * np.pi / n_phi
    tt, pp = np.meshgrid(t, p, indexing="ij")
    d = np.stack([np.sin(tt) * np.cos(pp), np.sin(tt) * np.sin(pp), np.cos(tt)], -1).reshape(-1, 3)
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    w = (np.sin(tt) * (top / n_theta) * (2 * np.pi / n_phi)).reshape(-1)
    return d, w
