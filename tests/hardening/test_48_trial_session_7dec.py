"""Defects found by trials of 7 December (a read of the last notes' leftovers and new users' trials):
compare.format_table raised KeyError on rows it was not made for."""

import pytest

from refracta import compare


def test_format_table_names_what_a_foreign_row_lacks():
    # A row of the user's own (or one of transparency()'s among shadows()'s) raised KeyError: 'p99_error'.
    with pytest.raises(ValueError, match=r"rows\[0\] lacks 'p99_error', 'nan_count', 'bytes_per_pixel', 'seconds'"):
        compare.format_table([{"method": "mine", "mean_error": 0.1}])
    shadow = {
        "method": "pcf",
        "kernel": 3,
        "reference": "ray",
        "mean_error": 0.1,
        "p99_error": 0.2,
        "light_leak": 0.0,
        "over_shadow": 0.0,
        "nan_count": 0,
        "bits_per_texel": 32,
        "seconds": 0.1,
    }
    transparency = {
        "method": "mboit",
        "mean_error": 0.1,
        "p99_error": 0.2,
        "nan_count": 0,
        "bytes_per_pixel": 16.0,
        "seconds": 0.1,
    }
    with pytest.raises(ValueError, match=r"rows\[1\] lacks 'kernel', 'reference'"):
        compare.format_table([shadow, transparency])
    with pytest.raises(ValueError, match=r"rows\[0\] lacks 'method'"):
        compare.format_table(["pcf"])
    assert compare.format_table([shadow]).splitlines()[1].startswith("pcf")
    assert compare.format_table([]).count("\n") == 0  # the header alone
