import famcc


def test_version_is_exposed():
    assert famcc.__version__.count(".") == 2
