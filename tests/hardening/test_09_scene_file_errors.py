"""Scene-file mistakes raise ValueError naming file, line and key (issue 13): unknown keys in
[camera], [sun], [sky], [atmosphere] were silently ignored (`vfovv = 3` rendered at 45 degrees),
`size = [32.7, 16.2]` was truncated, `camera = 5` raised TypeError and `size = [inf, 1]`
OverflowError without file or line."""

import pytest

import refracta

CAMERA = "[camera]\nposition = [0, 1, 0]\nlook_at = [10, 1, 0]\n"


def load(tmp_path, text):
    path = tmp_path / "scene.toml"
    path.write_text(text)
    return refracta.load_scene(path)


@pytest.mark.parametrize(
    "text, line, key, suggestion",
    [
        (CAMERA + "vfovv = 3\n", 4, r"\[camera\] vfovv", "vfov"),
        (
            CAMERA + "[sun]\ndirection = [0, 1, 0]\nradiance = [1, 1, 1]\nangular_diameterr = 1\n",
            7,
            r"\[sun\] angular_diameterr",
            "angular_diameter",
        ),
        (CAMERA + "[sky]\nhorizn = [1, 1, 1]\n", 5, r"\[sky\] horizn", "horizon"),
        (CAMERA + "[atmosphere]\nsurface_dtt = 3\n", 5, r"\[atmosphere\] surface_dtt", "surface_dt"),
        (
            CAMERA + '[[materials]]\nname = "a"\ntype = "diffuse"\nreflectanse = 0.5\n',
            7,
            r"\[\[materials\]\] #1 reflectanse",
            "reflectance",
        ),
        (
            CAMERA + '[[objects]]\ntype = "sphere"\ncentre = [5, 1, 0]\nradius = 1\nkdd = 0.5\n',
            8,
            r"\[\[objects\]\] #1 kdd",
            "kd",
        ),
    ],
)
def test_unknown_keys_name_file_line_and_the_likely_key(tmp_path, text, line, key, suggestion):
    with pytest.raises(ValueError, match=rf"scene.toml:{line}: .*{key}: unknown key .*did you mean {suggestion}\?"):
        load(tmp_path, text)


@pytest.mark.parametrize("size", ["[32.7, 16.2]", "[inf, 1]", "[nan, 2]", "[0, 10]", "[-4, 10]", "[4]", '["a", 1]'])
def test_a_bad_image_size_is_refused_not_truncated(tmp_path, size):
    with pytest.raises(ValueError, match=r"scene.toml:4: \[camera\] size: must be"):
        load(tmp_path, CAMERA + f"size = {size}\n")


def test_whole_float_sizes_are_exact(tmp_path):
    assert (load(tmp_path, CAMERA + "size = [32.0, 16]\n").camera.width, 16) == (32, 16)


def test_a_table_given_as_a_value_names_file_and_line(tmp_path):
    with pytest.raises(ValueError, match=r"scene.toml:1: \[camera\]: must be a table"):
        load(tmp_path, "camera = 5\n")


SKY = '[environment]\ntype = "physical_sky"\nsun_direction = [-0.5, 0.6, 0.6]\n'


@pytest.mark.parametrize(
    "text, line, key",
    [
        # Found as a new user: `visibility = true` loaded as 1 km of visibility (float(True)), the
        # string "20" as 20 km, `focal_length_mm = true` as a 1 mm lens: a TOML boolean or string
        # where a number belongs is refused, naming file, line and key, as every other number is.
        (CAMERA + SKY + "visibility = true\n", 7, r"\[environment\] visibility"),
        (CAMERA + SKY + 'visibility = "20"\n', 7, r"\[environment\] visibility"),
        (CAMERA + SKY + "aerosol = true\n", 7, r"\[environment\] aerosol"),
        (CAMERA + SKY + "scale = false\n", 7, r"\[environment\] scale"),
        (CAMERA + "focal_length_mm = true\n", 4, r"\[camera\] focal_length_mm"),
        (CAMERA + 'vfov = "20"\n', 4, r"\[camera\] vfov"),
        (CAMERA + "focal_length_mm = 50\nf_number = true\n", 5, r"\[camera\] f_number"),
        (CAMERA + "[atmosphere]\nsurface_dt = true\n", 5, r"\[atmosphere\] surface_dt"),
        (CAMERA + '[atmosphere]\nsurface_depth = "0.1"\n', 5, r"\[atmosphere\] surface_depth"),
        (CAMERA + '[atmosphere]\ncurved_earth = "6371e3"\n', 5, r"\[atmosphere\] curved_earth"),
    ],
)
def test_a_boolean_or_string_for_a_number_is_refused(tmp_path, text, line, key):
    with pytest.raises(ValueError, match=rf"scene.toml:{line}: {key}: must be a number"):
        load(tmp_path, text)


@pytest.mark.parametrize("radius", ["1", "0", "-5.0", "999.0"])
def test_curved_earth_takes_true_or_a_planets_radius(tmp_path, radius):
    # A trial's `curved_earth = 1` (TOML's 1 is not true) loaded as a 1 m Earth and failed only when
    # rendering, with n overflowing in its flat frame.
    message = r"scene.toml:5: \[atmosphere\] curved_earth: .*radius must be a planet's, at least 100000 m"
    with pytest.raises(ValueError, match=message):
        load(tmp_path, CAMERA + f"[atmosphere]\ncurved_earth = {radius}\n")
    assert load(tmp_path, CAMERA + "[atmosphere]\ncurved_earth = 6371000.0\n")[2].radius == 6371000.0
