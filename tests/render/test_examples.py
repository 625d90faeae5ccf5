"""The example scenes (refracta.examples): each builds and renders, and the hot road's mirage
shows the sky below the horizon."""

import numpy as np
import pytest

import refracta
from refracta import examples

WIDTH, HEIGHT = 48, 16


@pytest.mark.parametrize("name", sorted(examples.EXAMPLES))
def test_each_example_renders_finite_and_lit_through_its_field(name):
    example = examples.EXAMPLES[name](WIDTH, HEIGHT)
    assert example.name == name and example.description
    for transport in ("direct", "path"):
        image = refracta.render(
            example.scene,
            example.camera,
            example.field,
            transport=transport,
            spp=1,
            max_length=example.max_length,
            progress=False,
        )
        assert image.shape == (HEIGHT, WIDTH, 3)
        assert np.all(np.isfinite(image)) and image.min() >= 0.0
        assert image.mean() > 0.0  # lit: not black


# Issue 19: the demo scenes are photographs -- at least 640 px wide by default, lit by the physical
# sky whose air greys the distance, through a long lens over the road and the sea.
DEMO_WIDTH = 640  # [px]
LONG_LENS_VFOV = 2.5  # [deg] vertical field of view of a >= 400 mm lens on full frame at 2:1 or wider


@pytest.mark.parametrize("name", sorted(examples.EXAMPLES))
def test_each_example_is_a_telephoto_photograph_with_aerial_perspective_by_default(name):
    example = examples.EXAMPLES[name]()
    assert example.camera.width >= DEMO_WIDTH
    assert example.camera.vfov < LONG_LENS_VFOV
    assert example.scene.aerial_perspective is not None


# The wet road (issue 19): in the hot road's default view the rows below the horizon whose
# open-road pixels show the sky (or the mirrored far scene) instead of the road -- their camera
# rays turn above the hot asphalt and never meet it -- are at least a tenth of the image height.
BAND_FRACTION = 0.10  # the figure for "clearly visible" (it was 3 % with a 2.2 deg, 3:1 view)
# The band's radiance must exceed the road's seen through still air: the asphalt (albedo 0.06)
# returns 0.06 E / pi of the sun and sky irradiance E, the sky toward the sun several times more
# (a property of the scene's physical sky, not a tuned number).
MIRAGE_OVER_ROAD = 1.5  # the band at least 1.5x the asphalt's mean luminance
ASPHALT = (0.3, 3.4)  # [m] |z| of the asphalt between the centre line and the edge lines
OPEN_ROAD = 5000.0  # [m] the cars and poles stand nearer; the ridge is farther


def luminance(rgb):
    return rgb @ np.array([0.2126, 0.7152, 0.0722])


def _hot_road_band(example):
    """(rows below the horizon, open-road columns, band rows) of the example's view: a band row's
    camera ray through an open column turns above the road (traced to max_length, never descending
    through height 0)."""
    camera, field = example.camera, example.field
    horizon = camera.project(np.asarray(camera.position) + [1e7, 0.0, 0.0])[1]
    below = range(int(np.ceil(horizon)), camera.height)

    def open_ground(point):  # the sand, the asphalt or its paint (tops within 4 mm of y = 0), or the
        return point is not None and (abs(point[1]) < 0.01 or point[0] > OPEN_ROAD)  # far ridge

    # Open columns: with straight rays every pixel below the horizon sees the ground, nothing
    # standing on it (no car or pole; the ridge 9 km away meets the rows nearest the horizon at
    # fine resolutions, and is part of what the band mirrors).
    open_columns = [
        c for c in range(camera.width) if all(open_ground(camera.pick(example.scene, c + 0.5, v + 0.5)) for v in below)
    ]

    def turns_above_road(c, v):
        origin, direction = camera.ray(c + 0.5, v + 0.5)
        path = refracta.trace_ray(field, origin, direction, max_length=example.max_length, stop_height=0.0)
        return path.stop != "stop_height"

    middle = open_columns[len(open_columns) // 2]
    band = [v for v in below if turns_above_road(middle, v)]
    return below, open_columns, band


def test_hot_road_default_view_shows_a_wet_road_band_of_a_tenth_of_its_height():
    # The default view (640 x 320) at a quarter of its pixels: the same lens and aspect, so the
    # same field of view; the band's height fraction does not depend on the pixel count.
    example = examples.hot_road(160, 80)
    default = examples.hot_road()
    assert example.camera.vfov == pytest.approx(default.camera.vfov, rel=1e-12)
    camera, field = example.camera, example.field
    below, open_columns, band = _hot_road_band(example)
    assert len(open_columns) >= 5
    # The band starts at the horizon and is contiguous (one mirage, no gaps).
    assert band and band[0] == below.start and band == list(range(band[0], band[-1] + 1))
    assert len(band) / camera.height >= BAND_FRACTION, (len(band), camera.height)
    # It agrees with the critical angle arccos(n(0)/n(h_eye)) against the camera's ray elevations
    # (within a row: the ray's elevation changes by vfov/height per row).
    n0, n_eye = field.ior(np.array([[0.0, 0.0, 0.0], [0.0, camera.position[1], 0.0]]))
    theta_c = np.degrees(np.arccos(n0 / n_eye))
    middle = open_columns[len(open_columns) // 2]
    depression = -np.degrees(np.arcsin(camera.ray(middle + 0.5, band[-1] + 0.5)[1][1]))
    assert depression == pytest.approx(theta_c, abs=camera.vfov / camera.height)
    # And the image shows it: those rows of the open ground are brighter than the asphalt below
    # the band (pixels whose straight ray meets it between its centre line and edge lines).
    render = dict(transport="direct", spp=2, max_length=example.max_length, progress=False)
    image = luminance(refracta.render(example.scene, camera, field, **render))
    mirage = image[band][:, open_columns].mean()
    asphalt = [
        image[v, c]
        for v in range(band[-1] + 3, camera.height)
        for c in range(camera.width)
        if (p := camera.pick(example.scene, c + 0.5, v + 0.5)) is not None
        and abs(p[1]) < 0.01
        and ASPHALT[0] < abs(p[2]) < ASPHALT[1]
    ]
    assert len(asphalt) > camera.width
    assert mirage > MIRAGE_OVER_ROAD * np.mean(asphalt), (mirage, np.mean(asphalt))


# The wet road's cars (issue 19: "the inverted lower parts of cars ... clearly visible"): each
# stands beyond where the rays that turn above the asphalt begin to meet what stands on it, so
# below the car's foot in the image some rows see the car again, upside down. Traced: camera rays
# through the car's column below its foot that turn above the road and cross the car's plane
# (its x) between the road and the car's roof (1.8 m), never touching the asphalt on the way.
CAR_ROOF = 1.8  # [m] examples._car: the cabin's top
MIRRORED_ROWS = 3  # rows of the 160 x 80 view (0.026 deg each: ~0.2 m at 420 m), a visible band


def test_hot_road_cars_stand_over_their_mirrored_lower_parts():
    example = examples.hot_road(160, 80)
    camera, field = example.camera, example.field
    for x, z in examples.HOT_ROAD_CARS:
        column = camera.project([x, 0.5, z])[0]
        foot = int(np.ceil(camera.project([x, 0.0, z])[1]))
        mirrored = 0
        for v in range(foot, camera.height):
            origin, direction = camera.ray(column, v + 0.5)
            path = refracta.trace_ray(field, origin, direction, max_length=example.max_length, stop_height=0.0)
            height = _crossing_height(path, x)
            mirrored += height is not None and 0.0 < height < CAR_ROOF
        assert mirrored >= MIRRORED_ROWS, (x, z, mirrored)


def _crossing_height(path, x):
    """The height [m] at which a traced path first reaches the plane at `x` [m] (None if it ends
    before: at the sea or at max_length), linear between its nodes."""
    points = np.asarray(path.points)
    beyond = np.flatnonzero(points[:, 0] >= x)
    if not len(beyond) or beyond[0] == 0:
        return None
    a, b = points[beyond[0] - 1], points[beyond[0]]
    return float(a[1] + (x - a[0]) / (b[0] - a[0]) * (b[1] - a[1]))


def _column_heights(example, field, column, x):
    """Per image row (top first) of `column`: the height at which the camera ray, traced through
    `field` (rk45, the sea at height 0 stopping it), reaches the plane at x."""
    camera = example.camera
    heights = []
    for v in range(camera.height):
        origin, direction = camera.ray(column + 0.5, v + 0.5)
        path = refracta.trace_ray(field, origin, direction, max_length=example.max_length, stop_height=0.0)
        heights.append(_crossing_height(path, x))
    return heights


def _images(heights, top):
    """The runs of consecutive rows whose rays meet the plane between heights 0 and `top`, each as
    (rows, 'erect' or 'inverted'): erect where the height met rises from one row to the one above
    it, inverted where it falls (a row's orientation is that of the step to the row above)."""
    runs = []
    for v in range(1, len(heights)):
        below, above = heights[v], heights[v - 1]
        if below is None or above is None or not (0.0 <= below <= top and 0.0 <= above <= top):
            continue
        kind = "erect" if above > below else "inverted"
        if runs and runs[-1][1] == kind and runs[-1][0][-1] == v - 1:
            runs[-1][0].append(v)
        else:
            runs.append(([v], kind))
    return runs


# The superior mirage (issue 19): cold_sea's freighter, hull-down 20 km away, is seen erect and
# above it upside down. Camera rays through the column of the ship, traced through the inversion,
# meet the ship's plane at heights that rise row by row (the erect image), then fall (the
# inverted image above it); without the atmosphere they only rise.
SEA_VIEW = (160, 60)  # the default 640 x 240 at a quarter: the same lens and aspect, the same angles
INVERTED_SPAN = 2 / 3  # the inverted image shows at least 2/3 of the ship's height: the ship, not a sliver
# Rows of a 60-row view are 0.77/60 = 0.013 deg apart; at 20 km the inverted rays' heights change
# by ~2 m a row there (the profile's dh/de), so a run's span is sampled to within a row's step.


def test_cold_sea_shows_the_freighter_erect_and_upside_down_above_it_against_the_sky():
    example = examples.cold_sea(*SEA_VIEW)
    assert example.camera.vfov == pytest.approx(examples.cold_sea().camera.vfov, rel=1e-12)
    camera, field = example.camera, example.field
    x, z = examples.COLD_SEA_SHIP
    column = int(camera.project([x, examples.SHIP_HEIGHT / 2, z])[0])
    heights = _column_heights(example, field, column, x)
    runs = _images(heights, examples.SHIP_HEIGHT)
    erect = [rows for rows, kind in runs if kind == "erect"]
    inverted = [rows for rows, kind in runs if kind == "inverted"]
    assert erect and inverted, runs
    # The (largest) inverted image lies above an erect one (smaller rows are higher in the image) ...
    image = max(inverted, key=len)
    assert any(rows[0] >= image[-1] for rows in erect), runs
    # ... and shows most of the ship upside down, from near its top down toward its waterline.
    seen = [heights[v] for v in image] + [heights[image[0] - 1]]
    assert max(seen) - min(seen) >= INVERTED_SPAN * examples.SHIP_HEIGHT, seen
    # Against the sky: beside the ship, in a column through the open horizon (past the ship's
    # stern and the coast's headland), the rays of the inverted image's lower rows -- the
    # superstructure and funnel upside down -- meet nothing and run to max_length, where they see
    # the sky. At least half of its rows: the inverted hull at its top borders the band of sea
    # the inversion lifts into view (those rays come down onto the water 20-30 km out).
    stern = camera.project([x, examples.SHIP_HEIGHT / 2, z + 0.5 * 110.0 + 40.0])[0]
    open_column = int(np.ceil(stern))
    assert open_column < camera.width

    def sees_sky(v):
        origin, direction = camera.ray(open_column + 0.5, v + 0.5)
        path = refracta.trace_ray(field, origin, direction, max_length=example.max_length, stop_height=0.0)
        return path.stop == "max_length"

    against_sky = [v for v in image if sees_sky(v)]
    assert len(against_sky) >= len(image) / 2, (image, against_sky)
    assert against_sky == image[len(image) - len(against_sky) :], (image, against_sky)  # its lower part
    assert min(heights[v] for v in against_sky) > examples.SHIP_HULL  # above the hull: the superstructure
    # Without the atmosphere the same column shows the ship (what the bulge leaves of it) erect only.
    straight = _images(_column_heights(example, refracta.without_refraction(field), column, x), examples.SHIP_HEIGHT)
    assert all(kind == "erect" for _, kind in straight), straight


# Sun glitter (issue 19): examples.COLD_SEA_SUN lays the flank of the sun's glitter path on the sea
# in the frame's lower right (examples.py works out the facets' leans). In the rows wholly of sea --
# each one depression, so one strip of sky mirrored and one depth of air in front -- the eighth of
# the frame nearest the sun is at least GLITTER_CONTRAST times as bright as the eighth farthest
# from it. Cox & Munk's lobe alone (alpha^2 = 0.0081) makes the facets that mirror the sun e^-9.6
# rarer at the far eighth's centre (a sideways lean of 0.31 against 0.14); the sky mirrored and the
# air's in-scattered light, the same in both, dilute that to 14x (measured, 160 x 60, 1 spp). Without
# the glitter -- the sun at the same elevation behind the camera -- the same ratio is at most
# NO_GLITTER: the horizon sky's slow change with azimuth and the 1-spp noise of the mirrored sky
# (eighths of 18 rows x 20 columns differ by up to 10 %; measured 1.13-1.15 for four suns behind).
GLITTER_CONTRAST = 4.0
NO_GLITTER = 1.3


def _sea_eighths(example):
    """Mean luminance of the rows wholly of sea, in eighths of the frame's width (left to right)."""
    image, aovs = refracta.render(
        example.scene,
        example.camera,
        example.field,
        max_length=example.max_length,
        progress=False,
        aovs=["object_id"],
    )
    ids = aovs["object_id"]
    sea = ids[-1, example.camera.width // 2]  # the bottom row looks 0.29 deg down: the sea ~1 km out
    rows = np.flatnonzero(np.all(ids == sea, axis=1))
    assert len(rows) >= example.camera.height // 4  # the near sea: the frame's lower quarter or more
    return luminance(image[rows]).reshape(len(rows), 8, -1).mean(axis=(0, 2))


def test_cold_sea_glitters_on_the_suns_side():
    example = examples.cold_sea(*SEA_VIEW)
    elevation, azimuth = examples.COLD_SEA_SUN
    assert azimuth > 0.0  # to the right (+z), beyond the frame's edge: its glitter comes in from the right
    lit = _sea_eighths(example)
    assert np.argmax(lit) == 7, lit  # brightest nearest the sun
    assert lit[-1] >= GLITTER_CONTRAST * lit[0], lit
    examples.set_physical_sky(
        example.scene, examples.sun_direction(elevation, 180.0 - azimuth), visibility=examples.COLD_SEA_VISIBILITY
    )
    behind = _sea_eighths(example)
    assert behind.max() <= NO_GLITTER * behind.min(), behind


# Fata Morgana (issue 19): the sharp inversion just above the eye stacks the coast 20 km away --
# its foot erect, and above it the same heights again upside down, then erect and inverted once
# more (the 60-row view resolves all four).
FATA_MORGANA_FACE = 19500.0  # [m] a plane just before the coast's shore (20 km, wandering by ~60 m)
COAST_FOOT = 30.0  # [m] the heights of the shore the test follows (the inversion's base is 15 m)


def test_fata_morgana_stacks_the_coast_erect_and_inverted():
    example = examples.fata_morgana(*SEA_VIEW)
    assert example.camera.vfov == pytest.approx(examples.fata_morgana().camera.vfov, rel=1e-12)
    heights = _column_heights(example, example.field, example.camera.width // 2, FATA_MORGANA_FACE)
    kinds = [kind for _, kind in _images(heights, COAST_FOOT)]
    assert kinds[-2:] == ["inverted", "erect"], kinds  # from the bottom up: erect, then inverted above it
    assert kinds == ["inverted", "erect", "inverted", "erect"], kinds  # stacked: four images of the foot
    straight = _column_heights(
        example, refracta.without_refraction(example.field), example.camera.width // 2, FATA_MORGANA_FACE
    )
    assert [kind for _, kind in _images(straight, COAST_FOOT)] in ([], ["erect"])


# The stacked band as a photograph shows it: the duct stretches the cliffs' buttresses -- the side
# toward the low sun lit ~3x as much as the side away -- into columns of light and shade, and the
# forest's band is greener than the rock's. Measured in the 160 x 60 view at 4 spp: neighbouring
# columns over the cliffs differ by 31-38 % of their mean (uniformly painted, flat faces: 4-5 %; the
# forest's palisade 12 %), so 15 % is the bound; 4 spp direct leaves the column means (16 rows,
# 64 samples) a few percent of noise.
RIBBED_COLUMNS = 0.15
CLIFFS = {"granite": (-355.0, -262.0), "sandstone": (212.0, 355.0)}  # [m] along the shore, in view
FOREST = (55.0, 190.0)  # [m]


@pytest.mark.slow
def test_fata_morgana_band_shows_the_cliffs_ribs_as_columns_and_the_forest_green():
    example = examples.fata_morgana(*SEA_VIEW)
    camera = example.camera
    image = refracta.render(
        example.scene, camera, example.field, max_length=example.max_length, transport="direct", spp=4, progress=False
    )
    heights = _column_heights(example, example.field, camera.width // 2, FATA_MORGANA_FACE)
    rows = sorted({v for run, _ in _images(heights, COAST_FOOT) for v in run})
    band = image[rows]

    def columns(z0, z1):
        ends = sorted(camera.project([examples.FATA_MORGANA_COAST, 5.0, z])[0] for z in (z0, z1))
        return np.arange(int(np.ceil(ends[0])), int(np.floor(ends[1])))

    for name, (z0, z1) in CLIFFS.items():
        lum = luminance(band[:, columns(z0, z1)]).mean(axis=0)
        assert np.abs(np.diff(lum)).mean() > RIBBED_COLUMNS * lum.mean(), name
    rock = band[:, columns(*CLIFFS["granite"])].sum(axis=(0, 1))
    trees = band[:, columns(*FOREST)].sum(axis=(0, 1))
    assert trees[1] / trees[0] > rock[1] / rock[0] + 0.15  # g/r: 1.17 against 0.87 measured


# The green flash (issue 19): frames of at least 512 px, and the sky around the setting sun shown,
# not black. The disc's red is ~3000 times the sky's beside it (38 air masses dim the sun), ~12
# stops: the demo exposes for the sun, as photographers of the green flash do, by a film's response
# per channel (the disc's red saturates, its green does not: orange), and encodes by a display gamma
# of 2.6, which shows the sky ~11.6 stops down as a dark brown (sRGB's linear toe would leave it at
# ~0.01, black).
GREEN_FLASH_MIN_SIZE = 512  # [px] each frame
# Displayed luminance: 10/255, a dark tone above black (measured 0.055 at 64 px; sRGB's encoding
# of the same exposure 0.009).
VISIBLE = 0.04
NOT_WHITE = 0.7  # the clipped disc keeps its hue: its blue below 0.7 of its red (white: equal)


def test_green_flash_frames_are_large_and_show_the_sky_around_the_red_disc():
    from refracta import cli

    assert cli.GREEN_FLASH_SIZE >= GREEN_FLASH_MIN_SIZE
    elevation, vfov = cli.GREEN_FLASH_FRAMES[0]
    # The demo's frames at a few pixels, exposed together as the demo does. 64, not 32: at 32 px Open
    # Image Denoise's border effect (before refracta.denoise mirrored the image beyond its edges) had
    # lifted the sky 41 % above a 256-spp reference's and the median shown sky to 0.107; the sky
    # denoised right shows 0.097 at 32 px, 0.101 at 64 px, and 0.102 in the 512 px demo.
    size = 64
    frames = [cli.green_flash_frame(e, v, size, spp=4) for e, v in cli.GREEN_FLASH_FRAMES]
    image, shown = frames[0], cli.green_flash_display(frames)[0]  # the first: the whole flattened disc
    # The sky: pixels above the horizon whose radiance is far below the disc's (its corners).
    eye = examples.green_flash(size, size, elevation).camera.position
    look = np.radians(cli.GREEN_FLASH_LOOK[vfov])
    camera = refracta.Camera(eye, eye + [np.cos(look), np.sin(look), 0.0], vfov=vfov, width=size, height=size)
    horizon = camera.project(np.asarray(eye) + [1e7, 0.0, 0.0])[1]
    lum = luminance(image)
    sky = (np.arange(size)[:, None] + 0.5 < horizon) & (lum < 1e-3 * lum.max())
    assert sky.sum() >= size, sky.sum()
    assert np.median(luminance(shown)[sky]) > VISIBLE, np.median(luminance(shown)[sky])
    disc = shown[np.unravel_index(np.argmax(lum), lum.shape)]
    assert disc[0] >= disc[1] >= disc[2] and disc[2] < NOT_WHITE * disc[0], disc


# The glitter path under the setting sun (issue 19 section 5). The sun, 0.45 deg below the true
# horizon, reaches the water only along rising paths the refraction bends down onto it, so its light
# samples there launch along them (DirectLighting::launch_below_horizon). A facet mirrors the sun
# into a view meeting the water at a grazing gamma when it leans sideways by tan b = sin(dphi) cos e /
# (sin e + sin gamma): the path is ~alpha (e + gamma) ~ 0.05-0.1 deg wide each side of the sun's
# azimuth (Cox-Munk alpha 0.09 at examples.GREEN_FLASH_WIND; e ~ 0.3 deg, the sun seen from the
# water; gamma 0.2-0.35 deg in these rows), with Beckmann's tails beyond.
GLITTER_SIZE = 64  # [px] the demo's first frame (0.7 deg) at 64 x 64
GLITTER_SPP = 16
# The central quarter of the width (0.175 deg, the path) over the outer quarters (0.175-0.35 deg
# aside, its flanks and the reflected sky): measured 2.7-3.0 over four seeds at 16 spp; before the
# sun's samples were bent onto the water (they launched into the sea, the glitter left to rare BSDF
# hits weighted ~0.3 %) the sea's bands were within 15 % of each other. 2x stands between the two.
GLITTER_OVER_SEA = 2.0


def glitter_columns():
    from refracta import cli

    elevation, vfov = cli.GREEN_FLASH_FRAMES[0]
    example = examples.green_flash(GLITTER_SIZE, GLITTER_SIZE, elevation)
    look, eye = np.radians(cli.GREEN_FLASH_LOOK[vfov]), example.camera.position
    camera = refracta.Camera(
        eye, eye + [np.cos(look), np.sin(look), 0.0], vfov=vfov, width=GLITTER_SIZE, height=GLITTER_SIZE
    )
    # The sea's rows: from 0.2 deg below the frame's centre (+0.02 deg) down, below the disc's cut
    # at -0.140 deg apparent.
    first = GLITTER_SIZE // 2 + int(np.ceil((np.radians(0.2) / np.radians(vfov)) * GLITTER_SIZE))
    image = refracta.render(
        example.scene,
        camera,
        example.field,
        max_length=example.max_length,
        spectral=True,
        spp=GLITTER_SPP,
        progress=False,
        pixel_bounds=(0, first, GLITTER_SIZE, GLITTER_SIZE),
    )
    return luminance(np.maximum(image, 0.0)).mean(axis=0)


def test_the_sea_under_the_setting_sun_shows_its_glitter_path():
    columns = glitter_columns()
    sun_column = GLITTER_SIZE / 2  # the sun's azimuth is the view's
    band = GLITTER_SIZE // 4  # 0.175 deg: the path's width at the frame's foot
    path = columns[int(sun_column) - band // 2 : int(sun_column) + band // 2].mean()
    outer = np.concatenate([columns[: GLITTER_SIZE // 4], columns[-GLITTER_SIZE // 4 :]])
    assert path > GLITTER_OVER_SEA * outer.mean(), (path, outer.mean())
    # The brightest 16-px window lies under the sun (measured 28-35 for the sun's 32).
    assert abs(np.argmax(np.convolve(columns, np.ones(band) / band, "same")) - sun_column) <= band / 2
