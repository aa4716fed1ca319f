"""Posters in bands of columns and animation frames on Dask (floatcol/cluster.py).

A band fits the camera to the whole picture and draws its columns at the whole
picture's screen positions, so a tiled poster is the same, array for array, as one
render() of it; frames rendered by the workers of a LocalCluster are the same as
those rendered here."""
import sys

import numpy as np
import pytest

import floatcol as fc

EXPR = "3*sin(u*cos(v))"
DOM = dict(u=(-5, 5), v=(-5, 5))
ARRAYS = ("rgba", "side", "intensity", "depth", "u", "v", "w")


def _same(a, b):
    for name in ARRAYS:
        assert np.array_equal(getattr(a, name), getattr(b, name), equal_nan=True), name
    if a.shadow is not None:
        assert np.array_equal(a.shadow, b.shadow, equal_nan=True)
    assert a.stats["w_limits"] == b.stats["w_limits"]


TEX = np.random.default_rng(1).integers(0, 255, (32, 32, 3), dtype=np.uint8)


@pytest.mark.parametrize("kw", [
    dict(),
    dict(projection="perspective", lightsource=(315, 25), shadows=True),
    dict(antialias=3),
    dict(texture=TEX, contours=8),
    dict(antialias="area", projection="perspective"),
    dict(opacity=0.5),
    dict(vmin=-1.0, vmax=2.0, shading="lambert"),
], ids=["default", "persp-shadows", "subcolumns", "texture-contours", "area", "translucent",
        "limits"])
def test_a_tiled_poster_is_the_same_picture(kw):
    whole = fc.render(EXPR, **DOM, size=(203, 150), **kw)
    tiled = fc.render(EXPR, **DOM, size=(203, 150), tiles=5, **kw)
    assert tiled.stats["bands"] == 5
    _same(whole, tiled)


def test_a_tiled_poster_in_perspective_batches(monkeypatch):
    """Perspective planes in SIMD batches start each column's Newton iterations from
    the columns before it in its group of tiles (kernels/column.py guesses_for): the
    bands start at whole groups, so a poster is still the same picture."""
    from floatcol.cluster import bands
    from floatcol.kernels.layout import GROUP
    geometry = sys.modules["floatcol.passes.geometry"]
    kw = dict(projection="perspective", elev=35, azim=-50)
    scalar = fc.render(EXPR, **DOM, size=(203, 150), **kw)
    monkeypatch.setattr(geometry, "BATCH_MIN_SAMPLES", 0)
    whole = fc.render(EXPR, **DOM, size=(203, 150), **kw)
    tiled = fc.render(EXPR, **DOM, size=(203, 150), tiles=4, **kw)
    assert whole.stats["samples"] != scalar.stats["samples"]      # (batched)
    assert all(a % GROUP == 0 for a, _ in bands(203, 4))
    _same(whole, tiled)


def test_a_tiled_poster_of_lines_fields_and_objects():
    """A line drawing; a colour field with a wireframe (the field's range is the
    picture's); a height field with objects standing on it (their triangles
    rasterised at the whole picture's columns)."""
    yy, xx = np.mgrid[0:80, 0:90]
    hf = fc.HeightField(np.sin(xx / 7.0) * np.cos(yy / 9.0) * 3, u=(0, 10), v=(0, 10))
    for expr, kw in (("sin(u)*v", dict(u=(-3, 3), v=(-3, 3), method="horizon")),
                     ("sin(u)*v", dict(u=(-3, 3), v=(-3, 3), color="u - v", wireframe=8)),
                     (hf, dict(objects=[fc.tree(5, 5, 1.5), fc.box(2, 3, 1, 1, 1)]))):
        whole = fc.render(expr, size=(157, 110), **kw)
        tiled = fc.render(expr, size=(157, 110), tiles=4, **kw)
        assert np.array_equal(whole.rgba, tiled.rgba)
        assert np.array_equal(whole.side, tiled.side)
        if kw.get("color") is not None:
            assert whole.stats["c_limits"] == tiled.stats["c_limits"]


TWO = [("sin(u)*cos(v)", (-3, 3), (-3, 3)), ("0.4*u - 0.5", (-3, 3), (-2, 2))]


@pytest.mark.parametrize("kw", [
    dict(),
    dict(projection="perspective", lightsource=(315, 25), shadows=True),
    dict(cmap="magma", vmin=-1.0, vmax=1.0),
    dict(opacity=[0.6, 0.8]),
], ids=["default", "persp-shadows", "limits", "translucent"])
def test_a_tiled_poster_of_several_surfaces(kw):
    """render_many in bands: each surface's colormap spans the heights it shows in the
    whole picture (a band that saw other heights of either is drawn again), and the
    surface seen at each pixel is the whole picture's."""
    whole = fc.render_many(TWO, size=(157, 110), elev=25, **kw)
    tiled = fc.render_many(TWO, size=(157, 110), elev=25, tiles=4, **kw)
    assert tiled.stats["bands"] == 4
    _same(whole, tiled)
    assert np.array_equal(whole.stats["surface"], tiled.stats["surface"])
    assert set(np.unique(whole.stats["surface"])) >= {0, 1}       # both show


def test_a_tiled_poster_of_one_surface_in_render_many():
    whole = fc.render_many([TWO[0]], size=(120, 90))
    tiled = fc.render_many([TWO[0]], size=(120, 90), tiles=3)
    _same(whole, tiled)
    assert np.array_equal(whole.stats["surface"], tiled.stats["surface"])


def test_a_tiled_poster_of_layers_with_their_own_materials():
    layers = [fc.Layer(TWO[0][0], TWO[0][1:], fc.Material(cmap="plasma")),
              fc.Layer(TWO[1][0], TWO[1][1:], fc.Material(upper_color="tab:red",
                                                          vmin=-2, vmax=1))]
    whole = fc.render_many(layers, size=(120, 90))
    tiled = fc.render_many(layers, size=(120, 90), tiles=3)
    _same(whole, tiled)


def test_a_translucent_posters_layer_counts():
    whole = fc.render(EXPR, **DOM, size=(120, 90), opacity=0.5)
    tiled = fc.render(EXPR, **DOM, size=(120, 90), opacity=0.5, tiles=3)
    assert np.array_equal(whole.stats["layers"], tiled.stats["layers"])


def test_the_bands_colormap_is_the_pictures():
    """Each band alone would stretch the colormap over its own heights: the poster's
    bands take the picture's, and a band that saw other heights is drawn again."""
    whole = fc.render("u", u=(-4, 4), v=(-1, 1), size=(120, 60), elev=90)
    tiled = fc.render("u", u=(-4, 4), v=(-1, 1), size=(120, 60), elev=90, tiles=3)
    _same(whole, tiled)
    # the bands' own heights differ (u from -4 to 4 across the picture)
    from floatcol.cluster import _band_task
    band = _band_task([("u", (-4, 4), (-1, 1))], dict(size=(120, 60), elev=90), 0, 24, 120)
    assert band["stats"]["w_limits"][1] < whole.stats["w_limits"][1] - 4


@pytest.mark.parametrize("kw,message", [
    (dict(tiles=0), "tiles must be a whole number"),
    (dict(tiles="4"), "tiles must be a whole number"),
    (dict(client="localhost"), "client must be a dask.distributed Client"),
])
def test_tiles_and_client_say_what_to_fix(kw, message):
    with pytest.raises(ValueError, match=message):
        fc.render(EXPR, **DOM, size=(40, 30), **kw)


def test_columns_say_what_to_fix():
    from floatcol.renderer import render_scene
    from floatcol.scene import scene_from_options
    with pytest.raises(ValueError, match="columns 30..49 must lie in the picture's 0..39"):
        render_scene(scene_from_options([(EXPR, (-5, 5), (-5, 5))], size=(40, 30),
                                        columns=(30, 20)))


def test_a_scheduler_address_where_no_scheduler_answers(tmp_path, capsys):
    """--scheduler pointing at a service that is not a dask scheduler (found trying an
    address of this machine's network, where a web proxy answers): its answer's first
    bytes, read as a message's length, made distributed ask for exabytes, a MemoryError
    and its traceback. One line and exit 2, as any bad option; nothing written."""
    import socket
    import threading

    pytest.importorskip("distributed", reason="the dask extra (in the test extras): pip "
                        "install 'floatcol[dask]'")
    from floatcol.cli import main
    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen(1)

    def stranger():                      # (a web server, as the one found was)
        conn, _ = server.accept()
        conn.recv(1024)
        conn.sendall(b"HTTP/1.1 400 Bad Request\r\nconnection: close\r\n"
                     b"content-length: 0\r\n\r\n")
        conn.close()
    threading.Thread(target=stranger, daemon=True).start()
    address = "tcp://127.0.0.1:%d" % server.getsockname()[1]
    assert main(["gallery", "build", "-o", str(tmp_path / "g"), "--only", "saddle",
                 "--scheduler", address]) == 2
    server.close()
    # the half-made Client is closed at once: left to a garbage collection, its __del__
    # stopped distributed's event loop while the next test's LocalCluster started it,
    # and the suite hung (a clean clone's run)
    import gc

    from distributed import Client

    def clients():
        for c in gc.get_objects():
            try:
                if isinstance(c, Client):
                    yield c
            except ReferenceError:          # (a dead weak proxy among the objects: the
                continue                    # test failed so in a clean clone's run)
    assert all(c.status in ("closed", "newly-created") for c in clients())
    gc.collect()
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"floatcol: error: cannot reach the scheduler "
                                               f"'{address}'"), err
    assert not (tmp_path / "g").exists()


@pytest.fixture(scope="module")
def client():
    distributed = pytest.importorskip("distributed", reason="the dask extra (in the test "
                                      "extras): pip install 'floatcol[dask]'")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as c:
        yield c


def test_a_poster_on_two_workers(client):
    kw = dict(size=(300, 200), lightsource=(315, 25), shadows=True)
    whole = fc.render(EXPR, **DOM, **kw)
    tiled = fc.render(EXPR, **DOM, client=client, **kw)
    assert tiled.stats["bands"] == 4                  # two a worker
    _same(whole, tiled)


def test_several_surfaces_on_two_workers(client):
    whole = fc.render_many(TWO, size=(200, 150))
    tiled = fc.render_many(TWO, size=(200, 150), client=client)
    assert tiled.stats["bands"] == 4
    _same(whole, tiled)


def test_the_gallery_on_two_workers(client, tmp_path):
    """Each example a task: the script goes as text, its pictures come back as bytes;
    the same pictures as a build here, and the CLI's --scheduler does the same."""
    from PIL import Image

    from floatcol.cli import main
    from floatcol.gallery import build
    only = ["saddle", "gordon_figures"]
    here = build(tmp_path / "here", only=only, progress=False)
    there = build(tmp_path / "there", only=only, progress=False, client=client)
    assert there.failed == {} and here.failed == {}
    images = [img for ex in there.examples for img in ex.images]
    assert len(images) == 1 + 4
    assert images == [img for ex in here.examples for img in ex.images]
    for img in images:
        a = np.asarray(Image.open(tmp_path / "here" / img))
        b = np.asarray(Image.open(tmp_path / "there" / img))
        assert np.array_equal(a, b), img
    assert main(["gallery", "build", "-o", str(tmp_path / "cli"), "--only", "saddle",
                 "--scheduler", client.scheduler.address]) == 0
    assert (tmp_path / "cli" / "img" / "saddle.png").is_file()


def test_sixty_frames_on_two_workers(client, tmp_path):
    """The workers' frames, fetched in order and written to the MP4 as they come, are
    the frames drawn here."""
    import imageio_ffmpeg
    kw = dict(t=(0, 6.28), frames=60, size=(64, 48), progress=False,
              lightsource=lambda t: (t * 57.3, 30), shadows=True)
    here = fc.animate("sin(x*y + t)", ("x", -2, 2), ("y", -2, 2), **kw)
    there = fc.animate("sin(x*y + t)", ("x", -2, 2), ("y", -2, 2), client=client,
                       output=tmp_path / "c.mp4", **kw)
    assert len(there.frames) == 60
    for a, b in zip(here.frames, there.frames):
        assert np.array_equal(np.asarray(a), np.asarray(b))
    assert here.stats["samples"] == there.stats["samples"]
    assert len(list(imageio_ffmpeg.read_frames(str(tmp_path / "c.mp4")))) == 1 + 60


def test_a_flight_on_two_workers(client):
    """fc.fly_through(client=): the height field scattered to the workers once, a frame
    a task; the same frames as here, shadows and all."""
    from matplotlib.cbook import get_sample_data
    dem = get_sample_data("jacksboro_fault_dem.npz", asfileobj=False)
    kw = dict(frames=4, size=(64, 36), above=900, vert_exag=2, shadows=True, progress=False)
    way = [(15000, 2500), (15500, 9000), (17000, 12000)]
    here = fc.fly_through(dem, way, **kw)
    there = fc.fly_through(dem, way, client=client, **kw)
    assert len(there.frames) == 4
    for a, b in zip(here.frames, there.frames):
        assert np.array_equal(a, b)
    assert here.stats["samples"] == there.stats["samples"]
