"""The package's surface: every public name documented, surfscatter.Error a ValueError, the layout of the package."""

import inspect

import pytest

import surfscatter as ss


def doc_text(name, obj):
    """A docstring without pybind11's signature line."""
    lines = (obj.__doc__ or "").strip().splitlines()
    if lines and lines[0].startswith(name + "("):
        lines = lines[1:]
    return "\n".join(lines).strip()


@pytest.mark.parametrize("name", ss.__all__)
def test_every_public_name_and_member_has_a_docstring(name):
    obj = getattr(ss, name)
    assert doc_text(name, obj), f"surfscatter.{name} has no docstring"
    if inspect.isclass(obj):
        for member_name, member in vars(obj).items():  # what the class itself defines (not Exception's args)
            if not member_name.startswith("_"):
                assert doc_text(member_name, member), f"surfscatter.{name}.{member_name} has no docstring"


def test_the_package_docstring_states_the_units():
    for word in ("lambda_nm", "_deg", "micrometres", "surfscatter.Error"):
        assert word in ss.__doc__


def test_error_is_a_value_error_named_in_the_package():
    assert issubclass(ss.Error, ValueError)
    assert ss.Error.__module__ == "surfscatter"
    with pytest.raises(ValueError) as raised:
        ss.KCorrelation(0.1, 1.0, 0.5)
    assert str(raised.value) == "gamma must be between 1.01 and 100 (KC), got 0.5"
    assert "\n" not in str(raised.value)


def test_expected_names_are_exported():
    for name in ("Conductor", "KCorrelation", "GaussianAcv", "TabulatedPsd", "MapStatistics", "HeightMap", "read_height_map",
                 "synthesize", "fit_surface", "measured_statistics", "bsdf", "Bsdf", "direction", "render",
                 "read_photo", "write_photo", "read_camera", "undistort", "Board", "calibrate", "pose", "colorcorrect",
                 "compare", "set_max_threads", "Error"):
        assert name in ss.__all__, name
