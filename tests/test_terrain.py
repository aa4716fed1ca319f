"""Terrains from files (floatcol/terrain.py): DEM formats, north-up rows, degrees,
nodata, vertical exaggeration, the one-call picture and the CLI's terrain command."""
import os
import sys

import numpy as np
import pytest
from matplotlib.cbook import get_sample_data

import floatcol as fc
from floatcol.cli import main

JACKSBORO = get_sample_data("jacksboro_fault_dem.npz", asfileobj=False)


def corner_peak(n=41):
    """North-up heights (row 0 the north) with a peak at the north-east corner."""
    y, x = np.mgrid[0:n, 0:n]
    return 100.0 * np.exp(-((x - 0.8 * n) ** 2 + (y - 0.2 * n) ** 2) / 20.0)


def test_matplotlibs_sample_dem_in_metres_rows_south_to_north():
    hf = fc.read_dem(JACKSBORO)
    with np.load(JACKSBORO) as d:
        z = d["elevation"].astype(float)
    assert hf.dem["geographic"]
    (ua, ub), (va, vb) = hf.default_domain
    # 402 x 343 cells of 3 arc-seconds at 36.6 N: 30.05 km east-west, 31.81 km north-south
    assert ua == 0 and va == 0
    assert ub == pytest.approx(402 * 0.000833333 * 111320 * np.cos(np.radians(36.59)), rel=2e-3)
    assert vb == pytest.approx(343 * 0.000833333 * 110990, rel=2e-3)
    assert np.array_equal(hf.hf[0], z[-1]) and np.array_equal(hf.hf[-1], z[0])
    assert fc.read_dem(JACKSBORO, vert_exag=2).hf.max() == 2 * z.max()


def test_an_open_npz_reads_as_its_file(tmp_path):
    """matplotlib's get_sample_data("jacksboro_fault_dem.npz") hands an open NpzFile
    (its own terrain example's first line): read as its file is, not as an array of
    its keys ("got shape (7,) of <U9")."""
    from matplotlib.cbook import get_sample_data
    opened = fc.read_dem(get_sample_data("jacksboro_fault_dem.npz"))
    byname = fc.read_dem(JACKSBORO)
    assert opened.default_domain == byname.default_domain
    assert np.array_equal(opened.hf, byname.hf, equal_nan=True)
    np.savez(tmp_path / "bad.npz", a=np.zeros(3), b=np.ones(4), xmin=np.zeros(2))
    with np.load(tmp_path / "bad.npz") as data:
        with pytest.raises(ValueError, match="open .npz.*no height array"):
            fc.read_dem(data)
    np.savez(tmp_path / "odd.npz", elevation=np.zeros((3, 3)), xmin=np.zeros(2), xmax=1,
             ymin=0, ymax=1)
    with np.load(tmp_path / "odd.npz") as data:
        with pytest.raises(ValueError, match="open .npz.*cannot be read"):
            fc.read_dem(data)


def test_a_range_given_downward_is_the_grid_flipped():
    z = np.arange(12.0).reshape(3, 4) ** 1.5
    down = fc.HeightField(z, u=(0, 3), v=(2, 0))         # rows north to south
    up = fc.HeightField(z[::-1], u=(0, 3), v=(0, 2))
    assert down.default_domain == up.default_domain
    assert np.array_equal(down.hf, up.hf)
    left = fc.HeightField(z, u=(3, 0), v=(0, 2))
    assert np.array_equal(left.hf, z[:, ::-1])


def test_npy_png_and_npz_formats(tmp_path):
    from PIL import Image
    z = corner_peak().round()
    z[5, 5] = -9999
    np.save(tmp_path / "a.npy", z)
    a = fc.read_dem(tmp_path / "a.npy", extent=(0, 400, 0, 400), nodata=-9999)
    assert a.default_domain == ((0, 400), (0, 400)) and not a.dem["geographic"]
    assert np.isnan(a.hf[-6, 5]) and np.isfinite(a.hf).sum() == z.size - 1
    # a 16-bit greyscale PNG: its values are the heights
    img = (corner_peak() * 300).astype(np.uint16)
    Image.fromarray(img).save(tmp_path / "b.png")
    b = fc.read_dem(tmp_path / "b.png")
    assert np.array_equal(b.hf, img[::-1].astype(float))
    # an .npz with coordinate vectors, y ascending (south row first)
    np.savez(tmp_path / "c.npz", z=z[::-1], x=np.linspace(10, 50, 41), y=np.linspace(0, 40, 41))
    c = fc.read_dem(tmp_path / "c.npz", nodata=-9999)
    assert c.default_domain == ((10, 50), (0, 40))
    assert np.array_equal(np.nan_to_num(c.hf), np.nan_to_num(a.hf))


def test_geotiff_extent_nodata_and_degrees(tmp_path):
    tifffile = pytest.importorskip("tifffile", reason="the optional extra floatcol[geotiff]")
    z = corner_peak().astype(np.float32)
    z[0, 0] = -32768
    # GeoTIFF tags: pixel scale, a tie point (pixel 0, 0 at its corner: PixelIsArea),
    # GeoKeys (GTModelType 2 geographic, GTRasterType 1 area), GDAL's nodata text
    keys = [1, 1, 0, 2, 1024, 0, 1, 2, 1025, 0, 1, 1]
    extra = [(33550, "d", 3, (0.001, 0.001, 0.0), True),
             (33922, "d", 6, (0, 0, 0, 10.0, 45.0, 0), True),
             (34735, "H", len(keys), keys, True),
             (42113, "s", 0, "-32768", True)]
    tifffile.imwrite(tmp_path / "d.tif", z, extratags=extra)
    d = fc.read_dem(tmp_path / "d.tif")
    assert d.dem["geographic"] and np.isnan(d.hf[-1, 0])
    (ua, ub), (va, vb) = d.default_domain
    # 40 cells of 0.001 deg at 44.98 N: 3.157 km east-west, 4.444 km north-south
    assert ub == pytest.approx(40 * 0.001 * 111412.84 * np.cos(np.radians(44.98)), rel=1e-3)
    assert vb == pytest.approx(40 * 0.001 * 111132.954, rel=2e-3)
    # projected (GTModelType 1): the coordinates as they are, node centres
    keys[7] = 1
    extra[2] = (34735, "H", len(keys), keys, True)
    tifffile.imwrite(tmp_path / "e.tif", z, extratags=extra[:3])
    e = fc.read_dem(tmp_path / "e.tif")
    assert np.ravel(e.default_domain) == pytest.approx([10.0005, 10.0405, 44.9595, 44.9995])


def test_north_is_up_from_above():
    # from straight above (matplotlib's elev 90, azim -90: x right, y up), the peak
    # at the north-east corner lands top right
    plot = fc.terrain(corner_peak(), extent=(0, 40, 0, 40), elev=90, azim=-90,
                      proj_type="ortho", size=(200, 200), lightsource=None)
    lum = plot.rgba[..., :3].astype(float).sum(axis=2)
    r = plot.render
    w = np.where(r.side != 0, np.nan_to_num(r.intensity), np.nan)
    assert np.isfinite(w).sum() > 10000
    i, c = np.unravel_index(np.nanargmin(np.where(r.side != 0, r.depth, np.inf)), w.shape)
    assert i < 100 and c > 100                       # the nearest point: the peak's top
    assert lum.shape == (200, 200)


def test_terrain_defaults_and_auto_exaggeration():
    plot = fc.terrain(JACKSBORO, size=(200, 120))
    # relief (1st-99th percentile) about 0.63 km on 31.8 km: 0.08 * 31.8 / 0.63 = 4.0
    assert 2.5 <= plot.vert_exag <= 6.0
    assert (plot.render if plot.render is not None else plot.draw()).stats["box"] == (1, 1, 1)
    assert (plot.rgba[..., 3] > 0).mean() > 0.3
    flat = fc.terrain(np.zeros((5, 5)) + 3.0, size=(60, 40))
    assert flat.vert_exag == 1.0
    # a number given is the heights' factor, for a file as for a HeightField (it was
    # once ignored for files)
    one, three = (fc.terrain(JACKSBORO, vert_exag=x, size=(120, 80)).draw().rgba
                  for x in (1, 3))
    assert not np.array_equal(one, three)
    hf = fc.read_dem(JACKSBORO)
    assert np.array_equal(fc.terrain(hf, vert_exag=3, size=(120, 80)).draw().rgba, three)
    with pytest.raises(ValueError, match="vert_exag"):
        fc.terrain(JACKSBORO, vert_exag=0)
    # a relief too small for any finite exaggeration (found by tests/fuzzing.py: its
    # logarithm of infinity was an OverflowError)
    tiny = np.arange(16.0).reshape(4, 4) * 1e-300
    with pytest.raises(ValueError, match="vert_exag='auto'.*give vert_exag"):
        fc.terrain(tiny, extent=(0, 1e300, 0, 1e300))


def test_bad_files_are_value_errors(tmp_path):
    with pytest.raises(ValueError, match="does not exist"):
        fc.read_dem(tmp_path / "none.tif")
    with pytest.raises(ValueError, match="use .npy"):
        fc.read_dem(tmp_path / "x.csv")
    (tmp_path / "bad.npy").write_bytes(b"not numpy")
    with pytest.raises(ValueError, match="cannot be read"):
        fc.read_dem(tmp_path / "bad.npy")
    np.save(tmp_path / "one.npy", np.arange(5.0))
    with pytest.raises(ValueError, match="2-D array"):
        fc.read_dem(tmp_path / "one.npy")
    with pytest.raises(ValueError, match="extent"):
        fc.read_dem(np.zeros((3, 3)), extent=(0, 0, 1, 2))


def test_a_dem_too_big_to_draw_is_refused_from_its_header(tmp_path, monkeypatch):
    """Each reader checks the heights' count in the file's header against the machine's
    memory (terrain.BYTES_PER_HEIGHT each) before it decodes them: a 1.8 MB
    zlib-compressed TIFF of 30000 x 30000 zeros filled a 24 GiB machine. Here the
    machine is made small instead (16 x 12 heights need 18 KiB); the TIFF's and PNG's
    decoders are made to fail the test if they are reached."""
    from PIL import Image

    import sys

    import floatcol._memory as memory
    terrain = sys.modules["floatcol.terrain"]        # (fc.terrain is the function)
    z = np.zeros((12, 16), np.uint16)
    np.save(tmp_path / "a.npy", z)
    np.savez_compressed(tmp_path / "b.npz", elevation=z)
    np.savez_compressed(tmp_path / "c.npz", anything=z, x=np.arange(16.0))
    Image.fromarray(z).save(tmp_path / "d.png")
    files = ["a.npy", "b.npz", "c.npz", "d.png"]
    tifffile = pytest.importorskip("tifffile", reason="the optional extra floatcol[geotiff]")
    tifffile.imwrite(tmp_path / "e.tif", z, compression="zlib")
    files.append("e.tif")
    need = 12 * 16 * terrain.BYTES_PER_HEIGHT
    for name in files:          # (they read while the machine is as large as they need)
        assert fc.read_dem(tmp_path / name).hf.shape == (12, 16)

    def decoded(*a, **k):
        raise AssertionError("decoded before its size was checked")
    monkeypatch.setattr(memory, "machine_bytes", lambda: (need - 1) / memory.SHARE)
    monkeypatch.setattr(tifffile.TiffPage, "asarray", decoded)
    monkeypatch.setattr(Image.Image, "load", decoded)
    for name in files:
        with pytest.raises(ValueError, match=f"{name}': its 12 x 16 heights need about 0.0 GiB "
                                             "to draw, more than this machine has"):
            fc.read_dem(tmp_path / name)


def test_signalling_nans_in_a_file_are_holes_without_warnings(tmp_path):
    """A damaged file can hold signalling NaNs (found by flipping bytes of DEM files):
    casting or multiplying them warned "invalid value encountered", a second line on
    the CLI's stderr. They are holes like any NaN, and nothing warns."""
    import warnings
    z64 = corner_peak()
    z64[3, 4] = np.array([0x7FF0000000000001], dtype=np.uint64).view(np.float64)[0]
    z32 = corner_peak().astype(np.float32)
    z32[3, 4] = np.array([0x7F800001], dtype=np.uint32).view(np.float32)[0]
    np.save(tmp_path / "a.npy", z64)
    np.save(tmp_path / "b.npy", z32)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for name in ("a.npy", "b.npy"):
            hf = fc.read_dem(tmp_path / name, vert_exag=2)
            assert np.isnan(hf.hf[-4, 4]) and np.isfinite(hf.hf).sum() == z64.size - 1
        assert np.isnan(fc.HeightField(z32).hf[3, 4])


def test_a_damaged_npz_is_a_value_error_that_leaves_no_file_open(tmp_path):
    """np.load left the file of a damaged .npz open when it failed on it (found by
    byte-mutating DEM files): a ResourceWarning once collected."""
    import gc
    import warnings
    bad = tmp_path / "bad.npz"
    bad.write_bytes(b"PK\x03\x04" + bytes(40))          # a zip's magic, then nothing
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        with pytest.raises(ValueError, match="bad.npz' cannot be read"):
            fc.read_dem(bad)
        gc.collect()
    assert not [w for w in caught if issubclass(w.category, ResourceWarning)]


def test_a_damaged_geotiff_is_one_line_from_the_cli(tmp_path):
    """tifffile logs what it finds wrong in a damaged file (its own names) through
    Python's logging, which a command line without handlers prints to stderr: the CLI
    printed that line as well as its own. Run as a user runs it (a process of its own:
    pytest would catch the log records itself)."""
    import subprocess
    import sys
    tifffile = pytest.importorskip("tifffile", reason="the optional extra floatcol[geotiff]")
    good = tmp_path / "good.tif"
    tifffile.imwrite(good, corner_peak().astype(np.float32))
    data = bytearray(good.read_bytes())
    data[4:8] = (0xFFFFFF00).to_bytes(4, "little")    # the first IFD's offset: past the end
    bad = tmp_path / "bad.tif"
    bad.write_bytes(bytes(data))
    with pytest.raises(ValueError, match="bad.tif"):
        fc.read_dem(bad)
    out = tmp_path / "out.png"
    res = subprocess.run([sys.executable, "-c", "import sys; from floatcol.cli import main; "
                          "sys.exit(main(sys.argv[1:]))", "terrain", str(bad), "-o", str(out)],
                         capture_output=True, text=True, timeout=300)
    assert res.returncode == 2
    err = res.stderr.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("floatcol: error:"), res.stderr
    assert not out.exists()


def test_cli_terrain(tmp_path, capsys):
    out = tmp_path / "t.png"
    assert main(["terrain", JACKSBORO, "--size", "160x100", "--vert-exag", "2",
                 "--antialias", "area", "-o", str(out)]) == 0
    assert out.is_file() and "heights x2" in capsys.readouterr().out
    np.save(tmp_path / "h.npy", corner_peak())
    assert main(["terrain", str(tmp_path / "h.npy"), "--extent", "-84.4:-84.0:36.4:36.7",
                 "--size", "120x80", "-o", str(tmp_path / "g.png")]) == 0
    for argv in (["terrain", str(tmp_path / "missing.tif")],
                 ["terrain", JACKSBORO, "--vert-exag", "-1"],
                 ["terrain", JACKSBORO, "--extent", "1:2:3"]):
        bad = tmp_path / "bad.png"
        assert main(argv + ["-o", str(bad)]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and err[0].startswith("floatcol: error:")
        assert not os.path.exists(bad)


def test_a_dem_flown_over_in_one_call_and_one_command(tmp_path, capsys):
    p = fc.terrain(JACKSBORO, vert_exag=2, size=(160, 90),
                   fly=dict(position=(15000, 2500), heading=15, pitch=-10, above=900))
    p.save(tmp_path / "call.png")
    r = p.render
    assert r.stats["geometry"] == "lod"
    # the camera fc.fly puts there over the same (exaggerated) heights
    cam = fc.fly(fc.read_dem(JACKSBORO, vert_exag=2), (15000, 2500), heading=15, pitch=-10,
                 above=900, size=(160, 90))
    assert np.allclose(r.view.center, cam["center"]) and r.view.scale == cam["scale"]
    assert (r.side[-20:] != 0).all() and (r.side[:5] == 0).all()     # ground, then sky
    out = tmp_path / "fly.png"
    assert main(["terrain", JACKSBORO, "--vert-exag", "2", "--fly", "15000:2500",
                 "--heading", "15", "--above", "900", "--size", "160x90", "-o", str(out)]) == 0
    from PIL import Image
    assert np.array_equal(np.asarray(Image.open(out).convert("RGBA")), p.render.rgba)
    capsys.readouterr()
    for argv in (["--fly", "1:2:3:4"], ["--fly", "15000:2500", "--pitch", "95"],
                 ["--fly", "x:2"]):
        bad = tmp_path / "bad.png"
        assert main(["terrain", JACKSBORO] + argv + ["-o", str(bad)]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and err[0].startswith("floatcol: error:")
        assert not os.path.exists(bad)
    with pytest.raises(ValueError, match="position"):
        fc.terrain(JACKSBORO, fly=dict(heading=3))
    # an eye outside the DEM: above its nearest point's ground (its edge continued)
    hf2 = fc.read_dem(JACKSBORO, vert_exag=2)
    edge = float(hf2.evaluate(np.array([0.0]), np.array([2500.0]))[0])
    assert np.allclose(fc.fly(hf2, (-3000, 2500), above=900)["center"],
                       fc.fly(hf2, (-3000, 2500, edge + 900))["center"], rtol=0, atol=1e-9)
    # looking away from the DEM, the command says nothing of it is in view, and where
    # it lies
    assert main(["terrain", JACKSBORO, "--fly=15000:-5000:2000", "--heading", "180",
                 "--size", "64x36", "-o", str(out)]) == 0
    assert "nothing of the DEM is in view; it spans u 0 to 29978.4" in capsys.readouterr().err
    assert main(["terrain", JACKSBORO, "--fly=15000:-5000:2000", "--heading", "0",
                 "--size", "64x36", "-o", str(out)]) == 0
    assert "nothing" not in capsys.readouterr().err


def test_longitude_and_latitude_on_a_dem_in_degrees(tmp_path, capsys):
    """fc.lonlat puts a point given in degrees where read_dem put the DEM's heights (its
    metres from the south-west corner): a peak at one node of a north-up grid of
    0.001-degree cells is found at its longitude and latitude, the corners at the
    extent's. The CLI's --degrees draws what the call at the converted point draws, and
    --fly takes a negative longitude as a value."""
    z = np.zeros((61, 81))
    z[10, 30] = 500.0                              # row 10 from the north, column 30
    ext = (10.0, 10.08, 45.0, 45.06)
    hf = fc.read_dem(z, extent=ext)
    assert hf.dem["geographic"] and hf.dem["degrees"] == ext
    u, v = fc.lonlat(hf, 10.030, 45.050)
    assert float(hf.evaluate(np.array([u]), np.array([v]))[0]) == pytest.approx(500.0)
    (ua, ub), (va, vb) = hf.default_domain
    assert fc.lonlat(hf, 10.0, 45.0) == (0.0, 0.0)
    corner = fc.lonlat(hf, [10.0, 10.08], [45.0, 45.06])
    assert np.allclose(corner, [[ua, ub], [va, vb]], rtol=1e-12)
    assert ub == pytest.approx(0.08 * 78_850, rel=2e-3)       # a degree of longitude at 45°
    assert vb == pytest.approx(0.06 * 111_132, rel=2e-3)
    np.save(tmp_path / "z.npy", z)
    assert fc.lonlat(tmp_path / "z.npy", 10.03, 45.05, extent=ext) == (u, v)
    for dem, kw in ((tmp_path / "z.npy", {}), (fc.HeightField(z, u=(0, 8), v=(0, 6)), {})):
        with pytest.raises(ValueError, match="not degrees"):
            fc.lonlat(dem, 10.0, 45.0, **kw)
    with pytest.raises(ValueError, match="finite"):
        fc.lonlat(hf, float("nan"), 45.0)
    # Jacksboro's DEM is in degrees; the command line takes them with --degrees
    j = fc.lonlat(JACKSBORO, -84.3, 36.55)
    assert 0 < j[0] < 29978.5 and 0 < j[1] < 31719
    # a plot's height field (its heights exaggerated) is the same ground
    assert fc.lonlat(fc.terrain(JACKSBORO, vert_exag=2).surface, -84.3, 36.55) == j
    assert fc.read_dem(JACKSBORO).scaled(1, 1, 3).dem["vert_exag"] == 3
    with pytest.raises(ValueError, match="not degrees"):
        fc.lonlat(fc.read_dem(JACKSBORO).scaled(2, 1, 1), -84.3, 36.55)
    p = fc.terrain(JACKSBORO, vert_exag=2, size=(96, 54),
                   fly=dict(position=j, heading=45, above=900))
    out = tmp_path / "deg.png"
    assert main(["terrain", JACKSBORO, "--vert-exag", "2", "--degrees", "--fly",
                 "-84.3:36.55", "--heading", "45", "--above", "900", "--size", "96x54", "-o",
                 str(out)]) == 0
    from PIL import Image
    assert np.array_equal(np.asarray(Image.open(out).convert("RGBA")), p.draw().rgba)
    capsys.readouterr()
    for argv in (["--degrees"], ["--degrees", "--fly", "1:2"]):
        dem = JACKSBORO if len(argv) == 1 else str(tmp_path / "z.npy")
        assert main(["terrain", dem] + argv + ["-o", str(tmp_path / "bad.png")]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and err[0].startswith("floatcol: error:"), err
        assert not os.path.exists(tmp_path / "bad.png")


def test_a_flight_goes_at_a_steady_speed_through_its_waypoints():
    from floatcol.camera import _catmull_rom, flight
    flat = fc.HeightField(np.zeros((101, 101)), u=(0, 1000), v=(0, 1000))
    # two waypoints: a straight line, frames equally spaced, the eye above the ground,
    # heading north-east along it
    pos, heads, along = flight(flat, [(100, 100), (900, 900)], 5, above=50)
    assert np.allclose(pos[:, :2], np.linspace((100, 100), (900, 900), 5), atol=1e-9)
    assert np.allclose(pos[:, 2], 50.0) and np.allclose(heads, 45.0)
    assert np.allclose(along, np.linspace(0, 800 * np.sqrt(2), 5))
    # the curve passes through every waypoint; a clip along it goes at a steady speed
    # and turns smoothly (60 frames: the frames' steps within 1 % of each other; the
    # heading turns at most 14.8 degrees from one frame to the next, at the third
    # waypoint's sharp turn, where a polyline would turn by 101 degrees at once)
    way = np.array([(100, 100, 40), (500, 300, 80), (600, 800, 60), (200, 900, 40)], float)
    dense = _catmull_rom(way, 64)
    assert np.allclose(dense[::64], way)
    pos, heads, along = flight(flat, way, 60)
    steps = np.linalg.norm(np.diff(pos, axis=0), axis=1)
    assert steps.max() < 1.01 * steps.min()
    assert np.allclose(pos[[0, -1]], way[[0, -1]])
    turn = (np.diff(heads) + 180) % 360 - 180
    assert np.abs(turn).max() < 20
    # the frames' points and headings are the curve's own, not a polyline's: with 5x
    # the frames each turns a fifth as far (0.432 -> 0.086 degrees at most; from a
    # polyline of its points the heading stood still and then jumped 0.447 at both)
    bend = [(100, 100), (500, 300), (900, 100)]
    turns = [np.abs(np.diff(flight(flat, bend, f, above=10)[1])).max() for f in (600, 3000)]
    assert turns[1] < 0.3 * turns[0]
    # the first heading points toward the second waypoint (within 30 degrees: the
    # curve bends toward the third); a heading given is kept
    toward = np.degrees(np.arctan2(400, 200))
    assert abs(heads[0] - toward) < 30
    assert np.allclose(flight(flat, way, 7, heading=-30)[1], -30)


def test_a_closed_flight_loops_without_a_seam():
    """closed=True: round the waypoints and back to the first, as smoothly; the frames
    equally spaced all the way round, the last one step short of the first."""
    from floatcol.camera import flight
    flat = fc.HeightField(np.zeros((101, 101)), u=(0, 1000), v=(0, 1000))
    square = [(200, 200), (800, 200), (800, 800), (200, 800)]
    pos, heads, along = flight(flat, square, 40, closed=True, above=50)
    ring = np.vstack([pos, pos[:1]])                         # the seam: last -> first
    steps = np.linalg.norm(np.diff(ring, axis=0), axis=1)
    assert steps.max() < 1.01 * steps.min()
    assert np.allclose(pos[0], (200, 200, 50))
    # it turns once round (by 21.7 degrees a frame at most, at the corners), and no
    # more across the seam than at the other corners
    turn = (np.diff(np.append(heads, heads[0])) + 180) % 360 - 180
    assert abs(turn.sum()) == pytest.approx(360) and np.abs(turn).max() < 25
    assert abs(turn[-1]) <= 1.01 * np.abs(turn[:-1]).max()
    # the start repeated at the end is the same loop; fewer than 3 waypoints is no loop
    again = flight(flat, square + [(200, 200)], 40, closed=True, above=50)[0]
    assert np.allclose(again, pos)
    with pytest.raises(ValueError, match="three different waypoints"):
        flight(flat, [(200, 200), (800, 200), (200, 200)], 5, closed=True)


def test_a_flight_looking_ahead_turns_into_its_corners_early():
    """look_ahead: the camera looks toward the curve's point that far ahead: on a
    straight stretch that is the tangent; round a square's corners (48 frames, an
    eighth of the loop ahead) its largest turn from one frame to the next is 11.8
    degrees against the tangent's 18.9 (at one frame's distance ahead, 21.6: a look
    ahead smooths the turns from a few frames' distance on); before an L's corner it
    already looks past it, and at an open curve's end it looks along the end."""
    from floatcol.camera import flight
    flat = fc.HeightField(np.zeros((101, 101)), u=(0, 1000), v=(0, 1000))
    line = [(100, 100), (900, 900)]
    assert np.allclose(flight(flat, line, 9, above=10, look_ahead=200)[1], 45.0)
    square = [(200, 200), (800, 200), (800, 800), (200, 800)]
    turns = []
    for ahead in (0.0, 300.0):
        _, heads, _ = flight(flat, square, 48, above=10, closed=True, look_ahead=ahead)
        t = (np.diff(np.append(heads, heads[0])) + 180) % 360 - 180
        assert abs(t.sum()) == pytest.approx(360)
        turns.append(np.abs(t).max())
    assert turns[1] <= 0.7 * turns[0]
    # an open L: before the corner it already looks past it; at the end along the end
    pos, heads, _ = flight(flat, [(100, 100), (500, 100), (500, 900)], 41, above=10,
                           look_ahead=300)
    k = int(np.argmin(np.abs(pos[:, 0] - 400)))            # 100 before the corner
    assert 0.0 < heads[k] < 90.0                            # (the leg's own is 90)
    assert heads[-1] == pytest.approx(flight(flat, [(100, 100), (500, 100), (500, 900)],
                                             41, above=10)[1][-1], abs=1e-6)
    with pytest.raises(ValueError, match="look_ahead must be a distance of 0 or more"):
        flight(flat, line, 3, look_ahead=-1)


def test_a_flight_over_a_ridge_keeps_above_it():
    """Between two waypoints (u, v) the eye is never nearer the ground than half
    ``above``: a straight flight at 50 over a ridge 200 high goes over it."""
    from floatcol.camera import flight
    u = np.linspace(0, 1000, 201)
    ridge = 200.0 * np.exp(-((u - 500) / 60) ** 2)
    hf = fc.HeightField(np.tile(ridge, (201, 1)), u=(0, 1000), v=(0, 1000))
    pos, _, _ = flight(hf, [(100, 500), (900, 500)], 81, above=50)
    ground = hf.evaluate(pos[:, 0], pos[:, 1])
    assert np.all(pos[:, 2] >= ground + 25 - 1e-9)
    assert pos[40, 2] == pytest.approx(225.0, abs=1e-6)      # over the crest
    assert pos[0, 2] == pytest.approx(ground[0] + 50) and pos[-1, 2] == pytest.approx(
        ground[-1] + 50)
    # (u, v, w) waypoints are followed exactly, even under the ground
    pos, _, _ = flight(hf, [(100, 500, 10), (900, 500, 10)], 5)
    assert np.allclose(pos[:, 2], 10.0)


def test_a_flight_over_a_dem_in_one_call_and_one_command(tmp_path, capsys):
    from PIL import Image
    way = [(15000, 2500), (15500, 9000), (20000, 14000)]
    anim = fc.fly_through(JACKSBORO, way, frames=3, size=(96, 54), above=900, vert_exag=2,
                          output=tmp_path / "f.gif", progress=False)
    assert len(anim) == 3 and anim.stats["vert_exag"] == 2
    # each frame is fc.terrain's picture from that frame's eye (heights exaggerated once)
    for k in (0, 2):
        p = fc.terrain(JACKSBORO, vert_exag=2, fly=dict(
            position=tuple(anim.stats["positions"][k]), heading=anim.stats["headings"][k],
            size=(96, 54)))
        assert np.array_equal(anim.frames[k], p.rgba)
    assert np.allclose(anim.stats["positions"][0, :2], way[0])
    with Image.open(tmp_path / "f.gif") as im:
        assert im.n_frames == 3
    out = tmp_path / "cli.gif"
    argv = ["terrain", JACKSBORO, "--vert-exag", "2", "--above", "900", "--size", "96x54",
            "--frames", "3"] + [a for u, v in way for a in ("--fly", f"{u}:{v}")]
    assert main(argv + ["-o", str(out)]) == 0
    assert "3 frames, 96x54" in capsys.readouterr().out
    ahead = fc.fly_through(JACKSBORO, way, frames=3, size=(96, 54), above=900, vert_exag=2,
                           look_ahead=3000, progress=False)
    assert main(argv + ["--look-ahead", "3000", "-o", str(tmp_path / "ahead.gif")]) == 0
    assert not np.allclose(ahead.stats["headings"], anim.stats["headings"])
    with Image.open(tmp_path / "ahead.gif") as im:
        im.seek(1)
        mid = np.asarray(im.convert("RGB"))
    # the CLI's middle frame is the call's (its GIF colours 1.2 levels off on average),
    # not the one looking along the tangent (22 levels off)
    assert np.abs(mid.astype(int) - ahead.frames[1][..., :3]).mean() < 4
    assert np.abs(mid.astype(int) - anim.frames[1][..., :3]).mean() > 10
    capsys.readouterr()
    with Image.open(out) as im, Image.open(tmp_path / "f.gif") as ref:
        assert im.n_frames == 3                  # the same clip as the call's
        im.seek(2)
        ref.seek(2)
        assert np.array_equal(np.asarray(im.convert("RGB")), np.asarray(ref.convert("RGB")))
    for bad_argv in (["--fly", "15000:2500", "--fly", "15500:9000", "-o", "x.png"],
                     ["--fly", "15000:2500", "--fly", "15500:9000:3000", "-o", "x.gif"],
                     ["--fly", "15000:2500", "--fly", "15000:2500", "-o", "x.gif"],
                     ["--fly", "15000:2500", "--fly", "15500:9000", "--frames", "0", "-o",
                      "x.gif"],
                     ["--fly", "15000:2500", "-o", "x.gif"], ["-o", "x.mp4"],
                     ["--fly", "15000:2500", "--frames", "30", "-o", "x.png"],
                     ["--fly", "15000:2500", "--look-ahead", "500", "-o", "x.png"],
                     ["--fly", "15000:2500", "--fly", "15500:9000", "--look-ahead", "-5",
                      "-o", "x.gif"]):
        bad_argv[-1] = str(tmp_path / bad_argv[-1])
        assert main(["terrain", JACKSBORO] + bad_argv) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and err[0].startswith("floatcol: error:"), err
        assert not os.path.exists(bad_argv[-1])


@pytest.mark.parametrize("ext", [".mp4", ".gif"])
def test_a_long_flight_to_a_file_is_never_held(tmp_path, monkeypatch, ext):
    """To an MP4 or a GIF a flight's frames are written as they are rendered: while a
    clip too long to keep renders, at most two of its pictures are alive at a time
    (a GIF's: the GIF_BATCH quantized together more, here 3; kept, all of them are),
    and its frames are read back from the file."""
    import gc
    import weakref
    anim_mod = sys.modules["floatcol.animate"]
    real = anim_mod._collect
    peak = []

    def spy(made, *args):
        alive = []

        def tracked():
            for f, n in made:
                gc.collect()
                alive.append(weakref.ref(f))
                peak.append(sum(r() is not None for r in alive))
                yield f, n
        return real(tracked(), *args)
    monkeypatch.setattr(anim_mod, "_collect", spy)
    way = [(15000, 2500), (15500, 9000), (20000, 14000)]
    kw = dict(frames=6, size=(48, 28), above=900, vert_exag=2, progress=False)
    monkeypatch.setattr(anim_mod, "KEEP_BYTES", 0)
    monkeypatch.setattr(anim_mod, "GIF_BATCH", 3)
    anim = fc.fly_through(JACKSBORO, way, output=tmp_path / f"f{ext}", **kw)
    in_flight = 0 if ext == ".mp4" else 3
    assert max(peak) <= 2 + in_flight and len(peak) == 6
    assert not isinstance(anim.frames, list) and len(list(anim.frames)) == 6
    monkeypatch.setattr(anim_mod, "KEEP_BYTES", 2**30)
    peak.clear()
    kept = fc.fly_through(JACKSBORO, way, output=tmp_path / f"g{ext}", **kw)
    assert peak == [1, 2, 3, 4, 5, 6] and isinstance(kept.frames, list)
    for f, g in zip(anim.frames, kept.frames):
        # (measured: 2.5-3.3 levels from H.264; a GIF's quantized frames, exactly)
        if ext == ".gif":
            assert np.array_equal(f, np.asarray(anim_mod._quantized(g).convert("RGBA")))
        assert np.abs(f[..., :3].astype(int) - g[..., :3]).mean() < 5


@pytest.mark.parametrize("path, frames, words", [
    ([(15000, 2500)], 3, "at least two"),
    ([(15000, 2500), (15500, 9000, 2000)], 3, "all \\(u, v\\) or all"),
    ([(15000, 2500), (15000, 2500)], 3, "give a heading"),
    (None, 3, "waypoints"),
    ([(15000, 2500), ("x", 3)], 3, "path must be a number"),
    ([(15000, 2500), (15500, 9000)], 0, "frames must be a positive whole number"),
    ([(15000, 2500), (15500, 9000)], 10 ** 9, "frames must be at most 100000"),
    ([(15000, 2500), (15500, 9000)], dict(fly=(1, 2)), "not fly="),
    ([(15000, 2500)] * 10_001, 3, "at most 10000"),
])
def test_a_flight_that_cannot_be_flown_is_a_value_error(path, frames, words):
    extra = frames if isinstance(frames, dict) else {}
    frames = 3 if extra else frames
    with pytest.raises(ValueError, match=words):
        fc.fly_through(JACKSBORO, path, frames=frames, size=(32, 18), progress=False, **extra)


def test_fly_camera_looks_where_it_says():
    hf = fc.HeightField(np.zeros((11, 11)), u=(0, 1000), v=(0, 1000))
    eye = (500.0, 200.0, 30.0)
    kw = fc.fly(hf, eye, heading=30, pitch=-10, fov=60, size=(201, 101))
    r = fc.render(hf, **kw)
    vw = r.view
    # the viewpoint is the eye: d3 behind the centre along the view direction
    b, a = np.radians(30), np.radians(-10)
    ahead = np.array([np.sin(b) * np.cos(a), np.cos(b) * np.cos(a), np.sin(a)])
    assert np.allclose(np.array(vw.center) - vw.d3 * ahead, eye)

    def seen(heading_off, elev_deg, dist=400.0):
        h, e = np.radians(30 + heading_off), np.radians(elev_deg)
        p = np.array(eye) + dist * np.array([np.sin(h) * np.cos(e), np.cos(h) * np.cos(e),
                                             np.sin(e)])
        return vw.project(*p[:, None])
    # straight along the view direction: the centre; 20 deg right of it (at the
    # pitch): tan 20 / tan 30 of the half width to the right; the horizon at eye
    # level: tan 10 deg of the focal length above the centre
    c, row = seen(0, -10)
    assert c[0] == pytest.approx(100, abs=1e-6) and row[0] == pytest.approx(50, abs=1e-6)
    col, _ = vw.project(*(np.array(eye) + 400 * np.array(
        [np.sin(b + np.radians(20)), np.cos(b + np.radians(20)), 0]))[:, None])
    c_h, row_h = seen(0, 0)
    assert row_h[0] == pytest.approx(50 - 100 * np.tan(np.radians(10)) / np.tan(np.radians(30)),
                                     abs=1e-6)
    # the ground below the horizon is seen, the sky above it is not
    assert (r.side[70:] != 0).all() and (r.side[:20] == 0).all()
    assert col[0] > 100
    # position (u, v): the eye 'above' the ground there
    kw2 = fc.fly(hf, (500, 200), above=50)
    assert kw2["center"][2] == pytest.approx(50 + 2 * kw2["d1"] * np.sin(np.radians(-10)))
    with pytest.raises(ValueError, match="pitch"):
        fc.fly(hf, eye, pitch=95)
    with pytest.raises(ValueError, match="position"):
        fc.fly(hf, (1, 2, 3, 4))


def test_a_fly_picture_one_pixel_wide_sees_what_its_centre_ray_sees():
    """fly() fits the field of view to the picture's width less one pixel: a picture
    one pixel wide divided by zero (found by tests/fuzzing.py's terrain cases). Its
    field of view is now that of two pixels, as build_view fits a one-pixel picture:
    the centre ray, 30 degrees down, meets the flat ground; 30 degrees up, the sky."""
    from floatcol.terrain import guedes
    hf = fc.HeightField(np.zeros((11, 11)), u=(0, 1000), v=(0, 1000))
    for size in ((1, 1), (1, 5)):
        for pitch, ground in ((-30, True), (30, False)):
            kw = fc.fly(hf, (500.0, 200.0, 30.0), heading=0, pitch=pitch, size=size)
            assert np.isfinite(kw["scale"]) and kw["scale"] > 0
            r = fc.render(hf, **kw)
            mid = (size[1] - 1) // 2
            assert (r.side[mid, 0] != 0) == ground
            rgba, uv, _ = guedes(hf, (500.0, 200.0, 30.0), pitch=pitch, size=size,
                                 variant="brute")
            assert np.isfinite(uv[mid, 0, 0]) == ground


def test_guedes_variants_place_the_terrain_as_his_paper_says():
    """Guedes' section 5b with the correction of eq. 7 puts the terrain nearly where
    the brute-force ray caster of the same voxels does; without it, and the naive and
    standard algorithms, cells away (benchmarks/bench_terrain.py's table)."""
    from floatcol.terrain import guedes
    hf = fc.read_dem(JACKSBORO, vert_exag=2)
    cell = hf.default_domain[0][1] / (hf.hf.shape[1] - 1)
    cam = dict(heading=15, pitch=-30, fov=55, above=1500, size=(96, 54))
    _, exact, _ = guedes(hf, (15000.0, 2500.0), variant="brute", **cam)
    off = {}
    for v in ("standard", "naive", "uncorrected", "corrected"):
        rgba, uv, _ = guedes(hf, (15000.0, 2500.0), variant=v, **cam)
        both = np.isfinite(uv[..., 0]) & np.isfinite(exact[..., 0])
        assert both.mean() > 0.9 and (rgba[..., 3] == 255).mean() > 0.9
        off[v] = np.median(np.hypot(*(uv[both] - exact[both]).T)) / cell
    # measured at 320x180: 3.37, 2.30, 3.18 and 0.43 cells
    assert off["corrected"] < 0.8
    assert min(off["standard"], off["naive"], off["uncorrected"]) > 1.5
    with pytest.raises(ValueError, match="variant"):
        guedes(hf, (15000.0, 2500.0), variant="best", **cam)


def _far(u0, v0, **kw):
    """A 2 km terrain of gentle hills at (u0, v0), seen by a fly camera 60 m above it,
    with a texture of 2 m checks (1000 x 1000 texels: a red and a green one crossed)
    and the sun's shadows."""
    x = np.linspace(0, 2000, 201)
    X, Y = np.meshgrid(x, x)
    z = 30 * np.sin(X / 300) * np.cos(Y / 250)
    ii = np.indices((1000, 1000))
    tex = np.stack([ii[0] % 2, ii[1] % 2, 0.5 + 0 * ii[0]], -1).astype(float)
    hf = fc.HeightField(z, u=(u0, u0 + 2000), v=(v0, v0 + 2000))
    cam = fc.fly(hf, (u0 + 1000.0, v0 + 700.0), heading=10, pitch=-25, fov=50,
                 size=(240, 180), above=60)
    return fc.render(hf, texture=tex, lightsource=(300, 20), shadows=True, **cam, **kw)


def test_a_dem_far_from_the_origin_draws_as_at_the_origin():
    """A DEM in UTM metres (u 500 km, v 4 100 km from the origin) draws as the same
    DEM at the origin: its texture's checks and its shadows land on the same pixels
    (the G-buffer keeps u and v from the view's centre, layout.py G_U: float32 held
    them in 0.25-0.5 m steps there, a quarter of a texel), and Render.u, v give the
    seen points to a millimetre. Measured 2026-12-06: the two pictures bit for bit
    the same, u and v within 3e-7 m (before: 3.6 % of the pixels more than 8 levels
    apart, up to 17, the checks' edges jagged; u, v off by up to 0.016 m)."""
    near = _far(0.0, 0.0)
    far = _far(5e5, 4.1e6)
    d = np.abs(near.rgba.astype(int) - far.rgba).max(-1)
    assert (d > 2).mean() <= 0.001
    seen = near.side != 0
    assert seen.mean() > 0.9 and np.array_equal(seen, far.side != 0)
    assert np.abs(far.u[seen] - 5e5 - near.u[seen]).max() < 1e-3
    assert np.abs(far.v[seen] - 4.1e6 - near.v[seen]).max() < 1e-3
    assert np.mean(np.abs(far.shadow[seen] - near.shadow[seen]) > 0.5) <= 0.001
    assert far.u.dtype == np.float64


def test_a_height_fields_extremes_are_kept_for_its_last_domain():
    """A flight's frames are plots of one DEM: its extremes are found once (kept with
    it), and found again for another domain."""
    z = np.add.outer(np.arange(11.0), np.arange(11.0))      # w = row + column
    hf = fc.HeightField(z, u=(0, 10), v=(0, 10))
    first = hf.extremes(((0, 10), (0, 10)), n=1)
    assert hf.extremes(((0, 10), (0, 10)), n=1) is first
    assert [a.tolist() for a in first] == [[10.0, 0.0], [10.0, 0.0], [20.0, 0.0]]
    part = hf.extremes(((2, 5), (1, 3)), n=1)                # the nodes inside only
    assert [a.tolist() for a in part] == [[5.0, 2.0], [3.0, 1.0], [8.0, 3.0]]
    with pytest.raises(ValueError):
        first[2][0] = 0.0                                     # (shared: read-only)


def test_a_dem_file_read_again_unchanged_is_the_same_height_field(tmp_path, monkeypatch):
    """fc.terrain of a file that a plot still holds, unchanged (path, size, modification
    time) and with the same options, takes the height field read before (its pyramid
    made); another option, a changed file, or nothing holding it reads it again."""
    import gc
    import sys
    T = sys.modules["floatcol.terrain"]          # (fc.terrain is the function)
    reads = []
    real = T.read_dem
    monkeypatch.setattr(T, "read_dem", lambda *a, **k: (reads.append(1), real(*a, **k))[1])
    path = tmp_path / "h.npy"
    np.save(path, corner_peak())
    kw = dict(size=(64, 40), vert_exag=1.0)
    a = fc.terrain(str(path), **kw)
    b = fc.terrain(path, azim=-80, **kw)
    assert len(reads) == 1 and b.surface is a.surface
    c = fc.terrain(str(path), nodata=0.0, **kw)
    assert len(reads) == 2 and c.surface is not a.surface
    # the file changed: read again, and its picture shows the change
    np.save(path, 2.0 * corner_peak())
    st = os.stat(path)
    os.utime(path, ns=(st.st_atime_ns, st.st_mtime_ns + 10 ** 9))
    d = fc.terrain(str(path), **kw)
    assert len(reads) == 3 and not np.array_equal(d.rgba, a.rgba)
    del a, b, c, d
    gc.collect()
    fc.terrain(str(path), **kw).draw()
    assert len(reads) == 4
