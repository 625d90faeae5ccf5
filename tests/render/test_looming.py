"""Looming: a target below the geometric horizon shows above a cold sea with an inversion."""

import numpy as np

import refracta

EYE = 5.0
DISTANCE = 25000.0  # horizon distances sqrt(2 R h): 8.0 km (eye) + 11.3 km (10 m target) = 19.3 km


def target_pixels(field):
    scene = refracta.Scene()
    scene.add_ground(0.0, 80000.0, kd=(0.05, 0.1, 0.15))
    scene.add_box([DISTANCE, 5.0, 0.0], [50.0, 10.0, 400.0], kd=(0.9, 0.0, 0.0))
    scene.set_sky((0.6, 0.7, 0.8), (0.6, 0.7, 0.8))
    camera = refracta.Camera([0, EYE, 0], [DISTANCE, EYE, 0], vfov=0.4, width=4, height=48)
    image = refracta.render(scene, camera, field, progress=False, max_length=40000.0)
    return int(np.sum(image[..., 0] > 2 * image[..., 2]))


def test_target_beyond_the_horizon_looms_only_with_an_inversion():
    standard = refracta.CurvedEarth(refracta.PhysicalAtmosphere(t_ground=278.15))
    # Warm air over a cold sea: +12 K over the lowest 40 m (superior mirage, ORACLES.md).
    inversion = refracta.CurvedEarth(
        refracta.PhysicalAtmosphere(t_ground=278.15, inversion_dt=12.0, inversion_base=0.0, inversion_thickness=40.0)
    )
    assert target_pixels(standard) == 0
    assert target_pixels(inversion) >= 4
