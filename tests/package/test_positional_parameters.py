"""No bound function or constructor takes more than six parameters by position (issue 22 item 2):
the rest are keyword-only, so a call reads as what it sets. Read from the signatures pybind11
writes into each docstring (every overload's), as help() and the stubs show them."""

import inspect
import re
import warnings

import pytest

import refracta
from refracta import _core

MAX_POSITIONAL = 6
SIGNATURE = re.compile(r"^(?:\d+\. )?(\w+)\((.*)\)(?: -> .*)?$")


def top_level_parameters(inside: str) -> list[str]:
    """The parameters of a signature's parenthesis, split at its top-level commas."""
    parts, depth, current = [], 0, ""
    for ch in inside:
        depth += ch in "([{"
        depth -= ch in ")]}"
        if ch == "," and depth == 0:
            parts.append(current.strip())
            current = ""
        else:
            current += ch
    return parts + ([current.strip()] if current.strip() else [])


def positional_counts(doc: str) -> list[int]:
    """For each signature line of a docstring: how many parameters besides self come before '*'."""
    counts = []
    for line in doc.splitlines():
        match = SIGNATURE.match(line.strip())
        if not match:
            continue
        count = 0
        for parameter in top_level_parameters(match.group(2)):
            if parameter.startswith("*") or parameter == "/":
                break
            count += parameter.split(":")[0].strip() != "self"
        counts.append(count)
    return counts


def bound_callables():
    for name, value in vars(_core).items():
        if name.startswith("__"):
            continue
        if inspect.isclass(value):
            for member, attribute in vars(value).items():
                if callable(attribute) and (not member.startswith("_") or member == "__init__"):
                    yield f"{name}.{member}", attribute
        elif callable(value):
            yield name, value


def test_no_bound_function_takes_more_than_six_by_position():
    over = {}
    for name, function in bound_callables():
        worst = max(positional_counts(function.__doc__ or ""), default=0)
        if worst > MAX_POSITIONAL:
            over[name] = worst
    assert over == {}, f"bound functions taking more than {MAX_POSITIONAL} parameters by position: {over}"


def test_the_check_reads_signatures_as_pybind11_writes_them():
    # Two overloads: one of 7 by position (self not counted), one with a keyword-only tail; a
    # default holding commas inside brackets is one parameter.
    doc = (
        "f(*args, **kwargs)\nOverloaded function.\n\n"
        "1. f(self: X, a: int, b: int, c: int, d: int, e: int, f: int, g: tuple[int, int] = (1, 2)) -> None\n\n"
        "2. f(self: X, a: int, *, b: int = 3) -> None\n"
    )
    assert positional_counts(doc) == [0, 7, 1]


def test_a_model_takes_its_first_six_parameters_by_position():
    # LogisticProfile has 8 parameters: the first 6 by position as before; the 7th and 8th by
    # position still work for one release, with a DeprecationWarning naming the model.
    default = list(refracta.LogisticProfile().params.values())  # in param_names' order
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        first_six = refracta.LogisticProfile(*default[:MAX_POSITIONAL])
    with pytest.warns(DeprecationWarning, match=r"LogisticProfile: parameters after the 6th by position"):
        all_eight = refracta.LogisticProfile(*default)
    assert first_six.params == all_eight.params
