import pytest
from tests.geometry.cam_programs import program


@pytest.fixture
def prog_mm():
    return program("mm")


@pytest.fixture
def prog_deg():
    return program("deg", 15.0)
