"""refracta.render: images of a scene seen through an atmosphere."""

from __future__ import annotations

import copy
import math
import warnings
from collections.abc import Sequence
from typing import Callable

import numpy as np

from refracta import _core, _denoise, _options
from refracta._checks import flag, is_seed
from refracta._progress import progress_callback
from refracta._sweep import as_executor, map_ordered
from refracta._warn import deprecated


class SceneWarning(UserWarning):
    """A render whose scene is probably not what was meant: it has no light (the image is black),
    or its ground is away from the field's height 0 (the air's layers sit above or below it).
    Silence it with ``warnings.filterwarnings("ignore", category=refracta.SceneWarning)``."""


# How far the scene's ground or sea (else its lowest geometry) may lie from the field's height 0 [m]
# before render() warns: a hot road's surface layer e-folds over ~0.1 m (a typical
# layer), so a ground 0.1 m off already sits a whole e-folding above or below the air that makes
# the mirage.
GROUND_TOLERANCE = 0.1
# ... and only when the air between that ground and height 0 is layered: its mean |dn/dh| [1/m]
# above ten times the standard atmosphere's near the ground (~3e-8 /m). Air that steep is a ground
# layer the offset moves; calmer air looks the same a few metres up or down.
LAYER_GRADIENT = 3e-7


def _bounds(scene: _core.Scene, objects: bool = False):
    """The scene's bounds (lower, upper) -- with `objects`, its objects' (Scene.object_bounds: a
    ground or sea counts only when there is nothing else) -- or None when it holds no geometry."""
    try:
        return scene.object_bounds if objects else scene.bounds
    except ValueError:
        return None


def _check_reach(
    scene: _core.Scene, camera: _core.Camera, max_length: float, reach: str = "max_length", remedy: str = ""
) -> None:
    """The hint for a scene whose every object lies beyond the rays' reach: the nearest point of its
    bounding box is farther from the camera than max_length, so every ray stops in the air and the
    image shows only the sky (terrain or a coast tens of kilometres away with the default reach).
    The objects' box: a sea or ground around the camera reaches it, and hid a coast beyond reach.
    reach: what limits the rays, named in the warning (with its `remedy`)."""
    bounds = _bounds(scene, objects=True)
    if bounds is None:
        return
    lower, upper = (np.asarray(corner, dtype=float) for corner in bounds)
    eye = np.asarray(camera.position, dtype=float)
    nearest = float(np.linalg.norm(eye - np.clip(eye, lower, upper)))
    farthest = float(np.linalg.norm(np.maximum(abs(lower - eye), abs(upper - eye))))
    if math.isfinite(nearest) and nearest > max_length:
        warnings.warn(
            f"render: the nearest of the scene's objects (a ground or sea plane aside) is {nearest:.6g} m from "
            f"the camera, beyond the rays' reach {reach} = {max_length:g} m, so the image shows none of them "
            f"(a ground or sea within reach, and the sky); pass a larger "
            f"{remedy or 'max_length='} (its farthest point is {farthest:.6g} m away; a curved ray is a little longer)",
            SceneWarning,
            stacklevel=3,
        )


def _straight_over_a_sphere(field) -> bool:
    """Whether method 'straight' through `field` follows a spherical Earth's straight lines (C++
    straight_air): like curved rays they end after max_length; over a flat Earth they have none."""
    return isinstance(field, _core.IndexField) and math.isfinite(field.earth_radius)


def _check_frame_radius(frame, field, method: str) -> None:
    """A SceneWarning where the frame= of the 'geographic' readout flattens another Earth than the
    rays' field: its latitudes, longitudes and heights would then be of points the render did not see."""
    if field is not None and not isinstance(field, _core.IndexField):
        return  # the render names the field's type itself
    # Straight rays over a field's Earth are straight lines of that Earth's true geometry.
    ours = math.inf if field is None else float(field.earth_radius)
    theirs = float(getattr(frame, "earth_radius", math.inf))
    if ours == theirs or (math.isfinite(ours) and math.isfinite(theirs) and abs(ours - theirs) <= 1e-9 * ours):
        return
    warnings.warn(
        f"render: frame= flattens an Earth of radius {theirs:g} m but the rays go through "
        + ("straight (flat) air" if field is None else f"a field of earth_radius {ours:g} m")
        + ": the 'geographic' readout maps points the render did not see; give the frame and CurvedEarth one radius",
        SceneWarning,
        stacklevel=3,
    )


def _check_scene(scene: _core.Scene, camera: _core.Camera, field, method: str, where: str = "render") -> None:
    """The SceneWarning hints of render(): a scene without any light or sky; a camera at or below
    its ground or sea (Scene.ground_bounds); a camera shut in an opaque object that no light reaches
    (Scene._dark_enclosure; not for render_raster, whose alpha and shadows='none' let light in);
    and one whose ground or sea (Scene.ground_bounds; without one, its lowest geometry) lies more
    than GROUND_TOLERANCE from height 0 of the field the
    rays go through (every field, CurvedEarth's flattened heights too, puts the ground at y = 0)
    with layered air in between (mean ``|dn/dh|`` > LAYER_GRADIENT below the camera)."""
    if len(scene.lights) == 0:
        warnings.warn(
            f"{where}: the scene has no light and no sky, so the image is black; add one with "
            "scene.set_sky(...), set_sun, set_physical_sky, set_environment, add_point_light or "
            "an emission= geometry",
            SceneWarning,
            stacklevel=3,
        )
    bounds = _bounds(scene)
    # The eye at or below the scene's ground or sea: a trial's eye at sea level saw sky where the sea
    # lies (its rays start on the plane), below it the sea's underside. Over it, not beside it: a
    # flat terrain tile 22 km off is no ground under the camera (a trial).
    ground_box = scene.ground_bounds
    over = ground_box is not None and all(ground_box[0][a] <= camera.position[a] <= ground_box[1][a] for a in (0, 2))
    ground = float(ground_box[0][1]) if ground_box is not None else None
    # A terrain's ground under the eye (a trial's eye 1.7 m above sea level on a 1 500 m hillside saw
    # open sea: its rays started inside the hill).
    x, y, z = (float(v) for v in camera.position)
    terrain = scene.terrain_height(x, z)
    below = (terrain, "terrain") if terrain is not None and not y > terrain else None
    if below is None and ground is not None and over and not y > ground:
        below = (ground, "ground or sea")
    if below is not None:
        warnings.warn(
            f"{where}: the camera is at y = {y:g} m, at or below the scene's {below[1]} (y = {below[0]:g} m "
            "under it), so its rays start in or under it: the image is not what an eye above it sees; raise the "
            "camera: in scene coordinates scene.terrain_height(x, z) gives the terrain's y; a geo.LocalFrame's "
            "camera (frame.camera, Camera.geographic) takes heights above the ellipsoid, "
            "frame.ground_height(scene, (lat, lon)) plus the eye's above the ground",
            SceneWarning,
            stacklevel=3,
        )
    traced = method != "raster" and len(scene.lights) > 0 and below is None
    enclosure = scene._dark_enclosure((x, y, z)) if traced else None
    if enclosure is not None:  # a trial's eye 1 mm up, inside the hot road's 2 mm road slab: a black image
        warnings.warn(
            f"{where}: the camera at ({x:g}, {y:g}, {z:g}) m is inside object {enclosure}: rays in 256 directions "
            "from it all meet that opaque object's inside, and every light of the scene is at infinity outside it "
            "(sun, sky, environment), so the image is dark (no surface in it is lit; only the air's own glow, with "
            "aerial perspective): move the camera out of it",
            SceneWarning,
            stacklevel=3,
        )
    if field is None or method == "straight" or bounds is None:
        return
    # The scene's ground or sea where it has one (a wave sea's mean level, not its troughs: a trial's
    # 10 m/s sea at 0 was told to move 1.84 m up), else its lowest geometry.
    lowest = ground if ground is not None else float(bounds[0][1])
    if not (math.isfinite(lowest) and abs(lowest) > GROUND_TOLERANCE):
        return
    x, _, z = camera.position
    try:
        n = field.ior(np.array([[x, 0.0, z], [x, lowest, z]]))
        layered = abs(float(n[0] - n[1])) / abs(lowest) > LAYER_GRADIENT
    except (_core.NumericalError, ValueError):
        layered = True  # no air there at all: the scene is surely misplaced
    if layered:
        warnings.warn(
            f"render: the scene's {'ground' if ground is not None else 'lowest geometry'} is at y = {lowest:g} m, "
            "but the field's ground is at "
            f"height 0, so its ground layer lies {'below' if lowest > 0 else 'above'} the scene's "
            "ground; move the scene (add_obj(offset=...), add_ground(height=0)) so its ground is at y = 0",
            SceneWarning,
            stacklevel=3,
        )


def render_options(**options) -> _core.RenderOptions:
    """A _core.RenderOptions with the given fields set, validated by RenderOptions.validate: the
    package's one keyword rule (refracta._options.build; unknown names raise ValueError, a None
    value leaves a field that takes no None at its C++ default, 4.0 is 4 for a whole-number field)."""
    return _options.build(_core.RenderOptions, where="render", **options)


def warn_if_perturbed_refused(field, settings, camera, owner: str) -> None:
    """A SceneWarning where turbulence_trace='perturbed' cannot serve the render (the C++ rule:
    render/shimmer_cast.h perturbed_trace_refusal), which then traces the turbulence strictly."""
    refusal = _core._perturbed_trace_refusal(field, settings, camera)
    if refusal:
        warnings.warn(
            f"{owner}: turbulence_trace='perturbed' does not apply here -- {refusal}; the turbulence is traced "
            "strictly (the same image, at the strict cost)",
            SceneWarning,
            stacklevel=3,
        )


def render(
    scene: _core.Scene,
    camera: _core.Camera,
    field: _core.IndexField | None = None,
    method: str | None = None,
    transport: str | None = None,
    spp: int | None = None,
    max_depth: int | None = None,
    spectral: bool | None = None,
    seed: int | None = None,
    progress: bool | Callable[[int, int], None] = True,
    stats: dict | None = None,
    return_stats: bool = False,
    executor=None,
    tiles: None | int | tuple[int, int] = None,
    aovs: Sequence[str] | None = None,
    denoise: bool = False,
    frame=None,
    **options,
):
    """Render `scene` from `camera` through `field`; returns linear HDR radiance, float32 (H, W, 3),
    or with `aovs` the pair (image, {name: array}); with return_stats=True, the same followed by a
    refracta.RenderStats (samples, chords: Embree queries along camera paths, invalid_samples).
    method, transport, spp, max_depth, spectral, seed and the further keywords are fields of
    refracta.RenderOptions; None (or left out) keeps its default, defined there (method 'curved',
    transport 'direct', 1 spp, seed 0, RGB).

    aovs: names of per-pixel outputs to return beside the image, each averaged over the pixel's
    samples: 'albedo' -- (H, W, 3) the directional albedo (reflectance and transmittance, linear
    sRGB in [0, 1]) of the first surface each sample's path meets that is not a perfect mirror or
    glass; 'normal' -- (H, W, 3) its shading normal facing the path, world space (0 where the path
    met no such surface). Readouts (Python's view of cpp/refracta/render/readouts.h; float32 but
    where said): of the NEAREST hit among the pixel's samples (the sample of least path length, so
    a foreground and a background never blend into a point in the air; bit-identical for any
    thread count) -- 'distance' (H, W) the true length of the curved camera path to it [m] (over a
    CurvedEarth its flat-frame length scaled back by r / R along it, Simpson's rule: mm at 40 km),
    inf where no sample met anything;
    'position' (H, W, 3) the hit point in scene coordinates [m] (over a CurvedEarth its flat
    frame), NaN where none; 'object_id' (H, W) int32 the id of the
    geometry met (as Scene.add_* returned), -1 where none; 'geographic' (H, W, 3) float64 latitude,
    longitude [deg] and height [m] of that point through ``frame.to_geographic`` (frame: the
    scene's refracta.geo.LocalFrame, required with it), NaN where none; 'true_elevation' (H, W)
    [deg] of that point seen from the eye along a straight line in the TRUE geometry: over a
    CurvedEarth both points are mapped from the flat frame back onto the sphere (azimuthal
    equidistant about the scene origin, height h = R (exp(y'/R) - 1)) and the chord's angle is
    taken against the eye's local horizontal; on a flat Earth, the scene's straight line;
    'hidden_height' (H, W, 2) [m] how much of the vertical through that point the Earth's bulge
    hides from the eye: channel 0 without refraction, the true height where the eye's tangent to
    the sphere crosses it, R (sec(theta - theta0) - 1) for a central angle theta beyond the
    horizon's theta0 = acos(R / (R + h_eye)) (about (d - sqrt(2 R h_eye))^2 / (2R) at ground
    distance d), 0 nearer and on a flat Earth, NaN for an eye at or below height 0 (no tangent:
    a shore below sea level has its own water level, not the sea's); channel 1 with refraction, the true height there
    of the grazing ray -- the lowest ray from the eye that stays above the ground (y' = 0) for
    max_length of path, found by bisection on its elevation through the field's height-only air
    and traced exactly -- 0 up to where it touches the ground, NaN beyond its reach or where every
    ray meets the ground (a duct); 'images' (H, W) int32 the mirage multiplicity: along the pixel's
    column, rows meeting the same object are cut into monotone branches of true elevation (a
    turning row belongs to both branches it joins); the count of branches on the pixel's object
    whose range of true elevations holds the pixel's (how many times the column shows that line of
    sight to the object: 1 unmiraged, 2 or 3 in a mirage), 0 where none (with pixel_bounds, the
    bounds' whole columns are rendered for it, and RenderStats counts their samples).
    'apparent_elevation' and 'apparent_azimuth' (H, W) [deg]: the direction at the eye of the camera
    ray whose hit the pixel reads (the nearest sample's, so apparent and true elevation are one
    ray's; where no sample hit, the mean of the samples'): elevation above the horizontal plane (y), azimuth clockwise
    from the frame's north (-z) in [0, 360) (refracta.geo's conventions; a compass bearing at the eye
    is ``frame.bearing(aovs["apparent_azimuth"], camera.position)``, which differs away from the
    frame's origin by the meridians' convergence). And 'samples' (H, W) int32: how many
    camera samples each pixel's value averages (RenderOptions.sample_counts: spp, edge_spp where an
    edge was refined, the adaptive count; an adaptive pilot's samples only chose it), e.g. to see
    where adaptive sampling spent them. Not with method 'raster_march'.
    denoise: return the image denoised by Intel Open Image Denoise
    (refracta.denoise) with those albedo and normal as its guides (rendered for it whether asked
    for or not); in RGB renders pixels where no sample met such a surface (the sky) keep their
    noise-free values (spectral ones are noisy in colour there too, and are denoised; their
    samples can leave the sRGB gamut, negative channels, which are clipped to 0 first, as the
    demo and a display do). With pixel_bounds the denoiser sees the window alone, so its pixels
    are not the whole image's denoised ones (a trial: up to 15 % of the window's maximum on the
    cold sea at 4 spp); render a margin around the window (some 32 pixels) and crop it for those.
    Executor tiles (tiles=) are joined before denoising. A bright feature smaller than a pixel that
    the guides do not show (a distant lamp, a star, a glint) is taken for noise and loses most of its
    light, even converged (a 1.5 %-of-a-pixel lamp kept 13 % at 1024 spp: a trial): render those
    without denoise.
    guide_spp (RenderOptions.guide_spp, default there: 0): when above spp, the albedo and normal
    come from a pass of their own of guide_spp samples per pixel that stop at the first
    non-specular surface (no lighting), so they hold each pixel's edge coverage to that many
    samples, and denoise=True follows Open Image Denoise with refracta.denoise's guided filter,
    which rebuilds edges between surfaces from them (and smooths shadow edges at the feet of
    objects: see refracta.denoise). Measured on the hot road's hardest crop at 16 spp 'direct'
    against 4096 spp: denoised relative MSE 2.0x below the noisy image's, 5.0x with guide_spp=64;
    but that pass costs about as much CPU again as the image (0.7-1.7x on the RGB demo scenes), as 32
    spp would, which denoised gives 4.7x, and guided by its own samples 6.9x: at equal cost no
    gain, so it is off by default (benchmarks/bench_denoise.py, the README's table).

    method: 'curved' -- exact curved rays: every segment (camera ray, bounce, shadow ray toward a
    distant light) is the integrator's path (stratified for height-only fields, rk45 otherwise,
    to `tol` [m]) cut into chords tested against the scene -- at most `chord` [m] long and never
    farther than `sagitta` [m] from the path -- hits refined on the continuous path; height-only
    fields serve camera rays from one ElevationTable for the eye (table=False traces each pixel;
    over a CurvedEarth paths over 150 km end in the table where they leave the air, and spectral
    renders of 8 spp or more one table per dispersion scale; trace='rk45' forces rk45); rays end after
    `max_length` [m] and see the sky in their last direction (over a CurvedEarth turned into the
    world frame by the central angle: a sun or sky far beyond the horizon is where it should be;
    there a camera ray that ends in the air above every object goes on to where it leaves the air
    and sees the sky there, so a low sun stands where its refraction puts it whatever max_length).
    Over a flat Earth the sky stays where the path ends (a ray there may still turn back down), so
    a sun within a few degrees of the horizon lights the ground by the refraction of the first
    max_length of its path: exact at the default and beyond the air's top, but at 1 deg 6 % dark
    with 200 km and 14 % with 500 km (a trial, against L x solid angle x sin e): for long views
    of a low sun, a CurvedEarth (exact at any max_length).
    'straight' -- ray casting without atmosphere (the reference); with field=None both are straight.
    Over a field with an Earth radius (a CurvedEarth: the scene is its flat frame) the rays are the
    straight lines of the true geometry, bending toward the sky in the flat frame, so the Earth's
    bulge hides what it hides without air; they end after `max_length` like curved rays (the
    rays of refracta.without_refraction(field)). Over a flat Earth they have no max_length.
    'raster_march' -- the original editor's method: the scene rasterized from the camera (with
    `guard_band`), each pixel's curved ray marched ('rk45' to `tol`, or march='rk4' with `step` [m]
    for at most `max_steps` steps: the original's 0.3 m x 1000) until a step lands behind the depth
    buffer; that raster pixel's colour is shown.

    transport: 'direct' -- emitters seen directly and direct lighting (next-event estimation and
    BSDF sampling, power-heuristic MIS) at the first non-specular surface, mirror and glass chains
    followed up to max_depth; 'path' -- unidirectional path tracing with NEE and MIS. Both play
    Russian roulette from rr_depth scattering events on, 'direct' along its mirror and glass chains
    too (unbiased, but a glass sphere's pixels then scatter about their mean: raise rr_depth for
    long chains followed in full). max_depth counts scattering events (0: emitters only, 1: direct
    lighting; Mitsuba's max_depth is this + 1; default _core.RenderOptions().max_depth).
    spectral: 4 hero wavelengths per sample (Wilkie et al. 2014) with colours upsampled from RGB,
    converted to linear sRGB through the CIE 1931 observer. Through a field the air disperses: each
    sample keeps its hero wavelength only and traces every segment through
    refracta.dispersed_field(field, hero) (camera rays through an eye table per dispersion scale from
    8 spp, see method; 3.5-4.1x the RGB cost on examples.hot_road(64, 24) at 4-16 spp, a trial).
    spp: samples per pixel (1: pixel centres, whatever the seed, so renders averaged over seeds
    converge to the pixel's integral only from spp=2; more: a correlated multi-jittered pattern,
    Kensler 2013), seeded by `seed` per pixel (independent of the thread count). adaptive=True: the
    same width x height x spp samples, shared by a pilot of max(2, round(spp / 8)) per pixel within each 32-pixel block
    (every pixel at least spp / 2, the rest where the pilot varies; unbiased; spp >= 6;
    RenderOptions.adaptive, cpp/refracta/render/adaptive_sampling.h); off by default, and not used
    by denoise=True: on the demo scenes it does not lower the error (benchmarks/bench_denoise.py).
    edge_spp (RenderOptions.edge_spp, off by default): when above spp, every pixel at an edge
    between surfaces (its samples' first-hit albedo or normal differs from a neighbour's: the
    outlines of poles, booms, hulls) is rendered again as one pattern of edge_spp samples, the
    others keep spp: the staircases and combs of a few point samples become the coverage a sensor's
    pixel integrates, at the cost of the edges' pixels only (hot road poles, 640x320 'direct'
    denoised, against 256 spp: relative MSE 0.0146 at 4 spp, 0.0011 at spp=2, edge_spp=32 for 1.3x
    its CPU, 0.0015 at 16 spp for 3.1x; film.h EdgeRefinement). Textures are filtered
    over each sample's ray-cone footprint (texture_filter=False point-samples them). stats:
    deprecated (a dict to fill with the counts of RenderStats); pass return_stats=True. progress: a bar on stderr
    (True), a callable progress(done, total), or False. Runs on all cores with the GIL released;
    Ctrl-C stops it. Further keywords: any field of refracta.RenderOptions (max_length, chord,
    sagitta, tol, trace, table, tile, texture_filter, march, step, max_steps, guard_band, rr_depth,
    pixel_bounds=(x0, y0, x1, y1): render only pixels [x0, x1) x [y0, y1), each exactly as in the whole
    image, before denoise=True, which sees the window alone).

    executor, tiles: split the image into tiles rendered by `executor` (a dask.distributed Client,
    any concurrent.futures.Executor, or None: one after another here) and assembled into the
    image: bit-identical to a local render (every pixel has its own seed; a height-only field's
    ElevationTable is the whole image's in every tile, rebuilt by each; raster_march tiles each
    rasterize and shade the whole view and split only the march). tiles=(nx, ny): nx x ny
    tiles of near-equal size; tiles=n: square tiles of n pixels; None with an executor: 128-pixel
    tiles. Scene, camera and field are pickled to the workers (texture files by path: they must be
    readable there). progress then reports finished tiles; stats sums the tiles' counts. Not
    RenderOptions.tile (tile=, one letter short): the parallel loop's square of pixels per task.

    Warns (refracta.SceneWarning) when the scene has no light and no sky (a black image), and when
    a field is given (method not 'straight') and the scene's ground or sea (Scene.ground_bounds;
    without one, its lowest geometry) lies more than
    GROUND_TOLERANCE = 0.1 m from the field's height 0, where its ground should be, with layered
    air in between (mean ``|dn/dh|`` under the camera above LAYER_GRADIENT = 3e-7 /m, ten times the
    standard atmosphere's: a hot road's or a cold sea's ground layer); and when curved rays' max_length
    falls short of the nearest of the scene's geometry (the image then shows only sky).
    """
    if "integrator" in options:
        raise ValueError("render: 'integrator' is now 'trace' (the ray integrator: 'rk45' or 'stratified')")
    for name, given, kind in (("scene", scene, _core.Scene), ("camera", camera, _core.Camera)):
        if not isinstance(given, kind):  # was pybind's "_render(): incompatible function arguments"
            raise ValueError(f"render: {name} must be a refracta.{kind.__name__} (got {type(given).__name__})")
    if field is not None and not isinstance(field, _core.IndexField):
        raise ValueError(f"render: field must be a refracta index field or None (got {type(field).__name__})")
    if stats is not None:
        if not isinstance(stats, dict):
            raise ValueError(f"stats must be a dict to fill (got {type(stats).__name__})")
        deprecated("render(stats=dict) is deprecated: pass return_stats=True and read the returned RenderStats")
    own = dict(return_stats=return_stats, aovs=aovs, denoise=denoise, frame=frame, executor=executor, tiles=tiles)
    wanted = check_render_keywords(camera, method, **own)
    if denoise or any(name != "samples" for name in wanted):
        options["surface_aovs"] = True
    if "samples" in wanted:
        options["sample_counts"] = True
    if any(name in READOUT_NAMES for name in wanted):
        options["readouts"] = True
    settings = render_options(
        method=method, transport=transport, spp=spp, max_depth=max_depth, spectral=spectral, seed=seed, **options
    )
    warn_if_perturbed_refused(field, settings, camera, "render")
    if frame is not None:
        _check_frame_radius(frame, field, settings.method)
    rows = _whole_columns_for_images(settings, camera, wanted)
    if executor is not None or tiles is not None:
        image, counts = _render_tiled(scene, camera, field, settings, executor, tiles, progress)
    else:
        callback = progress_callback(progress, "rendering")
        # The binding takes None (no atmosphere: straight rays) through its shared_ptr argument, which
        # pybind11's signature, and so the generated stub, cannot mark as optional.
        image, counts = _core._render(scene, camera, field, settings, callback)  # type: ignore[arg-type]
    _check_scene(scene, camera, field, settings.method)  # with the image: a refused render needs no hint
    if field is not None and (settings.method != "straight" or _straight_over_a_sphere(field)):
        _check_reach(scene, camera, settings.max_length)
        march_reach = settings.step * settings.max_steps
        if settings.method == "raster_march" and settings.march == "rk4" and march_reach < settings.max_length:
            # The original editor's march stops after max_steps steps: 300 m with its settings.
            _check_reach(scene, camera, march_reach, "step x max_steps", "max_steps= (or march='rk45')")
    if stats is not None:
        stats.update({name: getattr(counts, name) for name in ("samples", "chords", "invalid_samples")})
    outputs = {}
    if settings.sample_counts:  # the last channel (renderer.h)
        outputs["samples"] = np.ascontiguousarray(image[..., -1].astype(np.int32))
        image = np.ascontiguousarray(image[..., :-1])
    if settings.surface_aovs or settings.readouts:
        outputs.update(_surface_outputs(image))
        if settings.readouts:
            outputs.update(_readouts(image, wanted, frame))
        image = np.ascontiguousarray(image[..., :3])
    if rows is not None:  # back to the rows asked for
        image = np.ascontiguousarray(image[rows])
        outputs = {name: np.ascontiguousarray(values[rows]) for name, values in outputs.items()}
    if denoise:
        image = _denoised(image, outputs, settings)
    result = image if aovs is None else (image, {name: outputs[name] for name in wanted})
    if return_stats:
        return (*result, counts) if aovs is not None else (image, counts)
    return result


def own_keywords() -> set[str]:
    """render()'s keywords that are not RenderOptions fields: scene, camera, field, progress,
    return_stats, aovs, denoise, frame, executor, tiles, stats."""
    import inspect

    fields = set(_options.fields(_core.RenderOptions))
    parameters = inspect.signature(render).parameters.items()
    return {name for name, p in parameters if p.kind is not p.VAR_KEYWORD} - fields


def check_render_keywords(
    camera: _core.Camera,
    method: str | None,
    *,
    return_stats=False,
    aovs=None,
    denoise=False,
    frame=None,
    executor=None,
    tiles=None,
) -> list[str]:
    """render()'s own keywords (those that are not RenderOptions fields) checked before any work,
    by render and by the editor for its render_options; returns the names aovs asks for."""
    wanted = _aov_names(aovs)
    flag(return_stats, "render: return_stats")  # "no" is truthy
    flag(denoise, "denoise")
    if "geographic" in wanted and not callable(getattr(frame, "to_geographic", None)):
        raise ValueError(
            "render: aovs 'geographic' needs frame=, the scene's refracta.geo.LocalFrame (its to_geographic maps "
            f"scene points to latitude, longitude and height; got frame={frame!r})"
        )
    if frame is not None and "geographic" not in wanted:
        raise ValueError(
            "render: frame= maps the 'geographic' readout; ask for it with aovs=[..., 'geographic'] (got "
            f"frame={frame!r} and aovs={aovs!r})"
        )
    surface = [name for name in wanted if name not in READOUT_NAMES]  # the readouts say so themselves
    if (denoise or surface) and method == "raster_march":
        raise ValueError(
            f"render: {'denoise=True' if denoise else f'aovs {surface}'} needs method 'straight' or 'curved' (the "
            "ray renderers give the first surface's albedo and normal and count samples; got method='raster_march')"
        )
    as_executor(executor)  # its kind: None, an Executor or a dask Client
    if tiles is not None:
        tile_bounds(camera.width, camera.height, tiles)
    return wanted


def _surface_outputs(image: np.ndarray) -> dict:
    """The albedo and normal channels of a render with surface_aovs (image channels 3:6 and 6:9)."""
    return {"albedo": np.ascontiguousarray(image[..., 3:6]), "normal": np.ascontiguousarray(image[..., 6:9])}


def _denoised(image: np.ndarray, outputs: dict, settings) -> np.ndarray:
    """`image` (H, W, 3) denoised as render(denoise=True) does it, with the render's own albedo and
    normal (`outputs`, rendered with settings.surface_aovs)."""
    if settings.spectral:
        image = np.maximum(image, 0.0)
    # Guides of more samples than the image (guide_spp) hold the edges' coverage: the guided filter
    # rebuilds the image's edges from them (refracta.denoise's `guided`).
    refine = settings.guide_spp > settings.spp
    clean = _denoise.denoise(image, outputs["albedo"], outputs["normal"], guided=refine)
    # Pixels none of whose samples met a scattering surface (the sky, seen directly or through
    # mirrors and glass) carry no Monte Carlo noise in RGB: they keep their values (the
    # denoiser would only blur the sky's gradient: 3.5x its error on the hot road). Spectral
    # samples each carry their own wavelengths (one through dispersive air), so there the sky
    # is noisy in colour and is denoised too (the green flash's sun, 16 spp against 4096:
    # relative MSE 1.0x -> 9.0x below the noisy image's, FLIP 1.0x -> 1.9x; bench_denoise.py).
    if not settings.spectral:
        untouched = ~np.any(outputs["normal"], axis=2)
        clean[untouched] = image[untouched]
    return clean


# The per-pixel readouts render(aovs=...) knows (render's docstring; cpp/refracta/render/readouts.h).
READOUT_NAMES = (
    "distance",
    "position",
    "object_id",
    "geographic",
    "apparent_elevation",
    "apparent_azimuth",
    "true_elevation",
    "hidden_height",
    "images",
)
# The per-pixel outputs render(aovs=...) knows, and what they are (render's docstring).
AOV_NAMES = ("albedo", "normal", *READOUT_NAMES, "samples")


def _readouts(image: np.ndarray, wanted: list[str], frame) -> dict[str, np.ndarray]:
    """The readouts from the render's channels (where each lies: _core._READOUT_CHANNELS, from
    readouts.h); 'images' and 'geographic' are worked out from them."""
    out = {}
    for name, (first, count) in _core._READOUT_CHANNELS.items():
        values = image[..., first] if count == 1 else image[..., first : first + count]
        out[name] = np.ascontiguousarray(values.astype(np.int32) if name == "object_id" else values)
    if "images" in wanted:
        out["images"] = _core._mirage_images(out["true_elevation"], out["object_id"])
    if "geographic" in wanted:
        geographic = np.full(out["position"].shape, np.nan)
        met = out["object_id"] >= 0
        if np.any(met):
            lat, lon, height = frame.to_geographic(out["position"][met].astype(np.float64))
            geographic[met] = np.stack([np.asarray(lat), np.asarray(lon), np.asarray(height)], axis=-1)
        out["geographic"] = geographic
    return out


def _whole_columns_for_images(settings, camera, wanted) -> slice | None:
    """The 'images' readout counts the mirage's branches down each pixel's whole column
    (_core._mirage_images): with pixel_bounds of fewer rows, settings are widened to the bounds'
    whole columns (so every pixel is as in the whole image, at the cost of those rows); returns the
    rows to cut back to, or None."""
    if "images" not in wanted or settings.pixel_bounds is None:
        return None
    x0, y0, x1, y1 = settings.pixel_bounds
    if (y0, y1) == (0, camera.height):
        return None
    settings.pixel_bounds = (x0, 0, x1, camera.height)
    return slice(y0, y1)


def _aov_names(aovs) -> list[str]:
    if aovs is None:
        return []
    if isinstance(aovs, str):
        raise ValueError(f"aovs must be a list of names, e.g. ['albedo', 'normal'] (got the string {aovs!r})")
    try:
        names = list(aovs)
    except TypeError:
        raise ValueError(f"render: aovs must be a list of names, e.g. ['albedo', 'normal'] (got {aovs!r})") from None
    unknown = [name for name in names if name not in AOV_NAMES]
    if unknown:
        raise ValueError(f"render: unknown aovs {unknown} (valid names: {', '.join(AOV_NAMES)})")
    if len(set(names)) != len(names):
        raise ValueError(f"render: aovs names repeated ({names})")
    return names


# Tile side [pixels] when an executor is given without tiles: a few to a few tens of tasks for
# the usual image sizes (each task rebuilds the eye's table, so far smaller tiles waste work).
_DEFAULT_TILE = 128


def tile_bounds(
    width: int, height: int, tiles: None | int | tuple[int, int], region: tuple[int, int, int, int] | None = None
) -> list[tuple[int, int, int, int]]:
    """Pixel bounds (x0, y0, x1, y1) of the tiles of a width x height image (or of `region`), row
    by row from the top left: tiles=(nx, ny) near-equal tiles, tiles=n squares of n pixels."""
    x0, y0, x1, y1 = region if region is not None else (0, 0, width, height)
    w, h = x1 - x0, y1 - y0
    if tiles is None:
        tiles = _DEFAULT_TILE
    if isinstance(tiles, bool):
        raise ValueError(f"tiles must be a tile size or (nx, ny) (got {tiles!r})")
    if isinstance(tiles, (int, np.integer)):
        if tiles < 1:
            raise ValueError(f"tiles must be a tile size >= 1 or (nx, ny) (got {tiles!r})")
        xs = list(range(x0, x1, int(tiles))) + [x1]
        ys = list(range(y0, y1, int(tiles))) + [y1]
    else:
        try:
            counts = list(tiles)
        except TypeError:
            counts = []
        if len(counts) != 2 or not all(is_seed(v) for v in counts):  # not (True, 1), not (2.0, 1)
            raise ValueError(f"tiles must be a tile size or (nx, ny) whole numbers (got {tiles!r})")
        nx, ny = (int(v) for v in counts)
        if not (1 <= nx <= w and 1 <= ny <= h) or (nx, ny) != tuple(tiles):
            raise ValueError(f"tiles (nx, ny) must be whole numbers in [1, {w}] x [1, {h}] (got {tiles!r})")
        xs = [x0 + (i * w) // nx for i in range(nx + 1)]
        ys = [y0 + (j * h) // ny for j in range(ny + 1)]
    return [(xs[i], ys[j], xs[i + 1], ys[j + 1]) for j in range(len(ys) - 1) for i in range(len(xs) - 1)]


def _render_tile(scene, camera, field, settings, bounds):
    """One tile on a worker: the image of `bounds` and the render's counts."""
    settings = copy.copy(settings)  # threads of one process share the caller's options
    settings.pixel_bounds = bounds
    return _core._render(scene, camera, field, settings, None)


def _render_tiled(scene, camera, field, settings, executor, tiles, progress):
    region = settings.pixel_bounds
    if region is not None:  # checked against the camera (RenderOptions.bounds_in) before sending work
        settings.bounds_in(camera.width, camera.height)
    bounds = tile_bounds(camera.width, camera.height, tiles, region)
    # Scene, camera, field and options reach each dask worker once (map_ordered's `shared`).
    outcomes = map_ordered(
        _render_tile,
        [(b,) for b in bounds],
        executor,
        progress,
        "rendering tiles",
        shared=(scene, camera, field, settings),
    )
    ox, oy = (region[0], region[1]) if region is not None else (0, 0)
    width = (region[2] - region[0]) if region is not None else camera.width
    height = (region[3] - region[1]) if region is not None else camera.height
    image = None  # as many channels as the tiles have (renderer.h's layouts)
    counts = _core.RenderStats()
    for (x0, y0, x1, y1), (ok, value) in zip(bounds, outcomes):
        if not ok:
            raise value[0]
        tile, tile_counts = value
        if image is None:
            image = np.empty((height, width, tile.shape[2]), dtype=np.float32)
        image[y0 - oy : y1 - oy, x0 - ox : x1 - ox] = tile
        counts = counts + tile_counts
    return image, counts
