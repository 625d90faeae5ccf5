"""The materials every BSDF test runs over: name -> (material, two_sided_transmission)."""

from refracta import shading

GOLD_ETA, GOLD_K = (0.18, 0.42, 1.37), (3.42, 2.35, 1.77)  # gold-like complex index at R, G, B

MATERIALS = {
    "diffuse": (lambda: shading.Diffuse((0.8, 0.5, 0.2)), False),
    "blinn_phong": (lambda: shading.BlinnPhong(0.3, 0.5, 20.0), False),
    "rough_conductor": (lambda: shading.RoughConductor(alpha=0.3), False),
    "rough_conductor_aniso": (lambda: shading.RoughConductor(alpha_u=0.1, alpha_v=0.4, eta=GOLD_ETA, k=GOLD_K), False),
    "rough_dielectric": (lambda: shading.RoughDielectric(alpha=0.3, ior=1.5), True),
    "rough_dielectric_aniso": (lambda: shading.RoughDielectric(alpha_u=0.15, alpha_v=0.4, ior=1.33), True),
    "plastic": (lambda: shading.Plastic((0.6, 0.3, 0.1)), False),
    "rough_plastic": (lambda: shading.Plastic((0.6, 0.3, 0.1), alpha=0.2), False),
    "principled": (
        lambda: shading.Principled((0.8, 0.4, 0.2), roughness=0.5, clearcoat=1.0, clearcoat_gloss=0.3, sheen=0.5),
        False,
    ),
    "principled_aniso": (
        lambda: shading.Principled((0.8, 0.4, 0.2), metallic=0.7, roughness=0.6, anisotropic=0.8),
        False,
    ),
    "thin_film": (lambda: shading.ThinFilm(400.0, 1.33, eta=1.5, alpha=0.25), False),
    "dielectric": (lambda: shading.Dielectric(1.5), True),
    "thin_dielectric": (lambda: shading.ThinDielectric(1.5), True),
    "conductor": (lambda: shading.Conductor(), False),
    "water": (lambda: shading.Water(), False),
    "water_interface": (lambda: shading.Water(12.0, temperature_c=5.0, salinity=0.0, body=False), True),
}

# Materials with a non-delta density (the chi-square test needs one).
SAMPLED = [name for name in MATERIALS if name not in ("dielectric", "thin_dielectric", "conductor")]
